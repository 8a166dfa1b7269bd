#include "harness/usda/layer_registry.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/usda/usda_parser.h"

namespace obscura::usda {

namespace {

namespace fs = std::filesystem;

std::string cacheKey(const std::string& identifier) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(fs::path(identifier), ec);
    return (ec ? fs::path(identifier) : absolute).lexically_normal().string();
}

}  // namespace

const Layer& LayerRegistry::addRoot(std::string_view text, const std::string& identifier) {
    return add(text, identifier);
}

const Layer& LayerRegistry::add(std::string_view text, const std::string& identifier) {
    auto parsed = parseLayer(text, identifier);
    if (auto* error = std::get_if<Error>(&parsed)) throw CompositionFailure{std::move(*error)};
    auto layer = std::move(std::get<std::unique_ptr<Layer>>(parsed));
    for (const Diagnostic& diagnostic : layer->diagnostics)
        diagnostics_.warn(diagnostic.kind, diagnostic.warning.where, diagnostic.warning.message);
    const Layer& result = *layer;
    layers_[cacheKey(identifier)] = std::move(layer);
    return result;
}

std::string LayerRegistry::resolve(const Layer& anchor, const std::string& assetPath) const {
    const fs::path asset(assetPath);
    if (asset.is_absolute()) return asset.lexically_normal().string();
    return (fs::path(anchor.identifier).parent_path() / asset).lexically_normal().string();
}

const Layer& LayerRegistry::open(const std::string& resolvedPath, const std::string& assetPath, const SourceLocation& at) {
    if (const auto it = layers_.find(cacheKey(resolvedPath)); it != layers_.end()) return *it->second;
    std::ifstream in(resolvedPath, std::ios::binary);
    std::error_code ec;
    if (!in || fs::is_directory(resolvedPath, ec))
        throw CompositionFailure{Error{at, "cannot open layer '" + assetPath + "' (resolved to '" + resolvedPath + "')"}};
    std::ostringstream text;
    text << in.rdbuf();
    return add(text.str(), resolvedPath);
}

const LayerStack& LayerRegistry::stackOf(const Layer& root) {
    if (const auto it = stacks_.find(&root); it != stacks_.end()) return *it->second;
    auto stack = std::make_unique<LayerStack>();
    std::vector<const Layer*> including;
    collect(root, *stack, including);
    return *(stacks_[&root] = std::move(stack));
}

void LayerRegistry::collect(const Layer& layer, LayerStack& stack, std::vector<const Layer*>& including) {
    including.push_back(&layer);
    stack.layers.push_back(&layer);
    for (const Reference& sublayer : layer.subLayers) {
        const Layer& child = open(resolve(layer, sublayer.assetPath), sublayer.assetPath, sublayer.where);
        if (std::find(including.begin(), including.end(), &child) != including.end())
            throw CompositionFailure{
                Error{sublayer.where, "sublayer cycle: '" + sublayer.assetPath + "' includes the layer that names it"}};
        collect(child, stack, including);
    }
    including.pop_back();
}

}  // namespace obscura::usda
