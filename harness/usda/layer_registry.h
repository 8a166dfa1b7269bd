// Opens each layer file once and assembles layer stacks: a layer above its sublayers.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "harness/usda/diagnostics.h"
#include "harness/usda/layer.h"

namespace obscura::usda {

struct LayerStack {
    std::vector<const Layer*> layers;  // strongest first: a layer, then each sublayer's stack in order
    const Layer& root() const { return *layers.front(); }
};

class LayerRegistry {
public:
    explicit LayerRegistry(DiagnosticSink& diagnostics) : diagnostics_(diagnostics) {}

    // The root layer, from text already in memory.
    const Layer& addRoot(std::string_view text, const std::string& identifier);
    // Where an asset path written in `anchor` points: relative paths are relative to anchor's folder.
    std::string resolve(const Layer& anchor, const std::string& assetPath) const;
    // The layer at a resolved path; `assetPath` and `at` say who asked, for the error if it is missing.
    const Layer& open(const std::string& resolvedPath, const std::string& assetPath, const SourceLocation& at);
    const LayerStack& stackOf(const Layer& root);

private:
    const Layer& add(std::string_view text, const std::string& identifier);
    void collect(const Layer& layer, LayerStack& stack, std::vector<const Layer*>& including);

    DiagnosticSink& diagnostics_;
    std::map<std::string, std::unique_ptr<Layer>> layers_;  // by normalized absolute path
    std::map<const Layer*, std::unique_ptr<LayerStack>> stacks_;
};

}  // namespace obscura::usda
