#include "harness/usda/layer_registry.h"

#include <algorithm>
#include <optional>

#include "assets/package_path.h"
#include "harness/usda/layer_reader.h"
#include "harness/usda/materialx_layer.h"

namespace obscura::usda {

namespace {

// Layers and packages are kept by their absolute paths, however an arc spells them.
std::string cacheKey(const std::string& identifier) { return assets::absoluteAssetPath(identifier); }

}  // namespace

const Layer& LayerRegistry::addRoot(std::string_view bytes, const std::string& identifier) {
    // The root layer is the stage: without it there is nothing to compose.
    Loaded root = add(bytes, identifier);
    if (Error* error = std::get_if<Error>(&root)) throw CompositionFailure{std::move(*error)};
    rootVariables_ = expressionVariablesOf(std::get<const Layer*>(root)->metadata);
    return *std::get<const Layer*>(root);
}

std::string LayerRegistry::expand(const Layer* anchor, const std::string& text, const SourceLocation& at) {
    if (!isVariableExpression(text)) return text;
    // Pcp's expression variables: the referencing (root) layer stack's over the anchor's own.
    ExpressionVariables variables = rootVariables_;
    if (anchor) variables.merge(expressionVariablesOf(anchor->metadata));
    auto value = evaluateVariableExpression(text, variables);
    if (auto* problem = std::get_if<ExpressionProblem>(&value)) {
        diagnostics_.warn("expression:" + text, at, problem->message + "; taken as written");
        return text;
    }
    return std::get<std::string>(value);
}

LayerRegistry::Loaded LayerRegistry::add(std::string_view bytes, const std::string& identifier) {
    if (isZipData(bytes)) {
        // A package opened as a layer: its root layer, named inside the package so that its
        // relative asset paths resolve there.
        std::string problem;
        const assets::UsdzPackage* archive = assets_.package(cacheKey(identifier), &problem);
        if (!archive) return Error{SourceLocation{identifier, 0, 0}, problem};
        if (archive->rootLayer().empty())
            return Error{SourceLocation{identifier, 0, 0}, "the package holds no .usd, .usda or .usdc layer"};
        Loaded root = load(assets::joinPackagePath(identifier, archive->rootLayer()));
        if (const Layer* const* layer = std::get_if<const Layer*>(&root)) packageRoots_[cacheKey(identifier)] = *layer;
        return root;
    }
    auto parsed = readLayer(bytes, identifier);
    if (Error* error = std::get_if<Error>(&parsed)) return std::move(*error);
    return &keep(std::move(std::get<std::unique_ptr<Layer>>(parsed)), cacheKey(identifier));
}

const Layer& LayerRegistry::keep(std::unique_ptr<Layer> layer, const std::string& key) {
    for (const Diagnostic& diagnostic : layer->diagnostics)
        diagnostics_.warn(diagnostic.kind, diagnostic.warning.where, diagnostic.warning.message);
    const Layer& result = *layer;
    layers_[key] = std::move(layer);
    return result;
}

std::string LayerRegistry::resolve(const Layer& anchor, const std::string& written, const SourceLocation& at) {
    return assets::anchorAssetPath(expand(&anchor, written, at), anchor.identifier);
}

const Layer* LayerRegistry::open(const std::string& resolvedPath, const Request& request) {
    Loaded loaded = load(resolvedPath);
    if (const Layer* const* layer = std::get_if<const Layer*>(&loaded)) return *layer;
    // As Pcp reports an asset it cannot open or read (PcpErrorInvalidSublayerPath,
    // PcpErrorInvalidAssetPath: "Could not open asset @x@ for reference introduced by @layer@<path>")
    // and composes the stage without the arc.
    const SourceLocation& at = request.where;
    const std::string site(request.site);
    const std::string arc = std::string(request.arc) + (site.empty() ? "" : " of <" + site + "> to");
    diagnostics_.warn(kindAt("unreadableLayer:<" + site + ">" + resolvedPath, at), at,
                      arc + " @" + std::string(request.assetPath) + "@ ignored: " + std::get<Error>(loaded).str());
    return nullptr;
}

LayerRegistry::Loaded LayerRegistry::load(const std::string& resolvedPath) {
    const std::string key = cacheKey(resolvedPath);
    if (const auto it = layers_.find(key); it != layers_.end()) return it->second.get();
    if (const auto it = packageRoots_.find(key); it != packageRoots_.end()) return it->second;
    if (const auto it = unreadable_.find(key); it != unreadable_.end()) return it->second;
    Loaded loaded = read(resolvedPath, key);
    if (const Error* error = std::get_if<Error>(&loaded)) unreadable_.emplace(key, *error);
    return loaded;
}

LayerRegistry::Loaded LayerRegistry::read(const std::string& resolvedPath, const std::string& key) {
    std::string problem;
    std::optional<std::string> bytes = assets_.read(key, &problem);
    if (!bytes) {
        // A file in a package is blamed on the package, as a missing file is on itself.
        const auto packaged = assets::splitPackagePath(resolvedPath);
        return Error{SourceLocation{packaged ? packaged->package : resolvedPath, 0, 0}, problem};
    }
    if (isMaterialXDocument(resolvedPath)) {
        auto parsed = readMaterialXLayer(*bytes, resolvedPath);
        if (Error* error = std::get_if<Error>(&parsed)) return std::move(*error);
        return &keep(std::move(std::get<std::unique_ptr<Layer>>(parsed)), key);
    }
    return add(*bytes, resolvedPath);
}

const LayerStack& LayerRegistry::stackOf(const Layer& root) {
    if (const auto it = stacks_.find(&root); it != stacks_.end()) return *it->second;
    auto stack = std::make_unique<LayerStack>();
    std::vector<const Layer*> including;
    collect(root, LayerOffset{}, *stack, including);
    return *(stacks_[&root] = std::move(stack));
}

void LayerRegistry::collect(const Layer& layer, const LayerOffset& toRoot, LayerStack& stack,
                            std::vector<const Layer*>& including) {
    including.push_back(&layer);
    stack.layers.push_back(&layer);
    stack.offsets.push_back(toRoot);
    for (const Reference& sublayer : layer.subLayers) {
        const Layer* child = open(resolve(layer, sublayer.assetPath, sublayer.where),
                                  Request{"sublayer", sublayer.assetPath, sublayer.where, ""});
        if (!child) continue;
        if (std::find(including.begin(), including.end(), child) != including.end())
            throw CompositionFailure{
                Error{sublayer.where, "sublayer cycle: '" + sublayer.assetPath + "' includes the layer that names it"}};
        collect(*child, toRoot.after(arcTimeOffset(layer, sublayer.layerOffset, *child)), stack, including);
    }
    including.pop_back();
}

const LayerOffset& LayerStack::offsetOf(const Layer& layer) const {
    const auto it = std::find(layers.begin(), layers.end(), &layer);
    return offsets.at(size_t(it - layers.begin()));
}

double timeCodesPerSecond(const Layer& layer) {
    for (const char* key : {"timeCodesPerSecond", "framesPerSecond"})
        if (const auto it = layer.metadata.find(key);
            it != layer.metadata.end() && !it->second.numbers.empty() && it->second.numbers.front() > 0.0)
            return it->second.numbers.front();
    return 24.0;
}

LayerOffset arcTimeOffset(const Layer& from, const LayerOffset& authored, const Layer& to) {
    return authored.after(LayerOffset{0.0, timeCodesPerSecond(from) / timeCodesPerSecond(to)});
}

}  // namespace obscura::usda
