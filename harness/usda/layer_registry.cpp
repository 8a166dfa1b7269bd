#include "harness/usda/layer_registry.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "harness/usda/layer_reader.h"
#include "harness/usda/materialx_layer.h"

namespace obscura::usda {

namespace {

namespace fs = std::filesystem;

std::string cacheKey(const std::string& identifier) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(fs::path(identifier), ec);
    return (ec ? fs::path(identifier) : absolute).lexically_normal().string();
}

// A file's bytes, or why there are none.
std::variant<std::string, Error> readFile(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return Error{SourceLocation{path, 0, 0}, "no such file"};
    std::ifstream in(path, std::ios::binary);
    if (!in || fs::is_directory(path, ec)) return Error{SourceLocation{path, 0, 0}, "cannot be read"};
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

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

std::variant<const UsdzPackage*, Error> LayerRegistry::package(const std::string& archivePath) {
    const std::string key = cacheKey(archivePath);
    if (const auto it = packages_.find(key); it != packages_.end()) return it->second.get();
    auto bytes = readFile(archivePath);
    if (Error* error = std::get_if<Error>(&bytes)) return std::move(*error);
    std::string problem;
    auto opened = UsdzPackage::open(std::move(std::get<std::string>(bytes)), &problem);
    if (!opened) return Error{SourceLocation{archivePath, 0, 0}, problem};
    return (packages_[key] = std::move(opened)).get();
}

LayerRegistry::Loaded LayerRegistry::add(std::string_view bytes, const std::string& identifier) {
    if (isZipData(bytes)) {
        // A package opened as a layer: its root layer, named inside the package so that its
        // relative asset paths resolve there.
        auto archive = package(identifier);
        if (Error* error = std::get_if<Error>(&archive)) return std::move(*error);
        const std::string& inner = std::get<const UsdzPackage*>(archive)->rootLayer();
        if (inner.empty())
            return Error{SourceLocation{identifier, 0, 0}, "the package holds no .usd, .usda or .usdc layer"};
        Loaded root = load(joinPackagePath(identifier, inner));
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
    const std::string assetPath = expand(&anchor, written, at);
    // "other.usdz[inner.usda]": the archive resolves like any file, the part inside as written.
    if (auto packaged = splitPackagePath(assetPath))
        return joinPackagePath(resolve(anchor, packaged->first), fs::path(packaged->second).lexically_normal().string());
    const fs::path asset(assetPath);
    if (asset.is_absolute()) return asset.lexically_normal().string();
    if (auto inPackage = splitPackagePath(anchor.identifier))
        return joinPackagePath(inPackage->first,
                               (fs::path(inPackage->second).parent_path() / asset).lexically_normal().string());
    return (fs::path(anchor.identifier).parent_path() / asset).lexically_normal().string();
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
    std::variant<std::string, Error> bytes;
    if (auto packaged = splitPackagePath(resolvedPath)) {
        auto archive = package(packaged->first);
        if (Error* error = std::get_if<Error>(&archive)) return std::move(*error);
        std::string problem;
        std::optional<std::string> entry = std::get<const UsdzPackage*>(archive)->read(packaged->second, &problem);
        if (!entry) return Error{SourceLocation{packaged->first, 0, 0}, problem};
        bytes = std::move(*entry);
    } else {
        bytes = readFile(resolvedPath);
    }
    if (Error* error = std::get_if<Error>(&bytes)) return std::move(*error);
    if (isMaterialXDocument(resolvedPath)) {
        auto parsed = readMaterialXLayer(std::get<std::string>(bytes), resolvedPath);
        if (Error* error = std::get_if<Error>(&parsed)) return std::move(*error);
        return &keep(std::move(std::get<std::unique_ptr<Layer>>(parsed)), key);
    }
    return add(std::get<std::string>(bytes), resolvedPath);
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
