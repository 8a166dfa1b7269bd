// Opens each layer file once and assembles layer stacks: a layer above its sublayers.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "harness/usda/diagnostics.h"
#include "harness/usda/layer.h"
#include "harness/usda/usdz_package.h"

namespace obscura::usda {

struct LayerStack {
    std::vector<const Layer*> layers;  // strongest first: a layer, then each sublayer's stack in order
    const Layer& root() const { return *layers.front(); }
};

class LayerRegistry {
public:
    explicit LayerRegistry(DiagnosticSink& diagnostics) : diagnostics_(diagnostics) {}

    // The root layer, from its bytes already in memory (text, crate or a USDZ package).
    const Layer& addRoot(std::string_view bytes, const std::string& identifier);
    // Where an asset path written in `anchor` points: relative paths are relative to anchor's
    // folder, and inside a package ("a.usdz[b.usda]") to the folder in the package.
    std::string resolve(const Layer& anchor, const std::string& assetPath) const;
    // The layer at a resolved path; `assetPath` and `at` say who asked, for the error if it is missing.
    const Layer& open(const std::string& resolvedPath, const std::string& assetPath, const SourceLocation& at);
    const LayerStack& stackOf(const Layer& root);

private:
    // `at` blames the arc that asked for the layer when its package is unreadable.
    const Layer& add(std::string_view bytes, const std::string& identifier, const SourceLocation& at);
    // Registers a layer read under `key`, passing on its diagnostics.
    const Layer& keep(std::unique_ptr<Layer> layer, const std::string& key);
    const UsdzPackage& package(const std::string& archivePath, const SourceLocation& at);
    void collect(const Layer& layer, LayerStack& stack, std::vector<const Layer*>& including);

    DiagnosticSink& diagnostics_;
    std::map<std::string, std::unique_ptr<Layer>> layers_;  // by normalized absolute path
    std::map<const Layer*, std::unique_ptr<LayerStack>> stacks_;
    std::map<std::string, std::unique_ptr<UsdzPackage>> packages_;  // by normalized archive path
    std::map<std::string, const Layer*> packageRoots_;                // a package's path -> its root layer
};

}  // namespace obscura::usda
