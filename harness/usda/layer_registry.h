// Opens each layer file once and assembles layer stacks: a layer above its sublayers.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "assets/asset_reader.h"
#include "harness/usda/diagnostics.h"
#include "harness/usda/layer.h"
#include "harness/usda/variable_expression.h"

namespace obscura::usda {

struct LayerStack {
    std::vector<const Layer*> layers;  // strongest first: a layer, then each sublayer's stack in order
    // offsets[i] takes times of layers[i] to the root layer's: the sublayers' layer offsets, and the
    // ratio of time codes per second where a sublayer's differ from the layer naming it.
    std::vector<LayerOffset> offsets;
    const Layer& root() const { return *layers.front(); }
    const LayerOffset& offsetOf(const Layer& layer) const;
};

// Time codes per second of a layer, as Sdf reads them: timeCodesPerSecond, else framesPerSecond,
// else 24.
double timeCodesPerSecond(const Layer& layer);
// What an arc or sublayer (written in `from`, with `authored`) does to times of `to`: the authored
// offset, scaled as well by from's time codes per second over to's.
LayerOffset arcTimeOffset(const Layer& from, const LayerOffset& authored, const Layer& to);

class LayerRegistry {
public:
    explicit LayerRegistry(DiagnosticSink& diagnostics) : diagnostics_(diagnostics) {}

    // The root layer, from its bytes already in memory (text, crate or a USDZ package).
    const Layer& addRoot(std::string_view bytes, const std::string& identifier);
    // Where an asset path written in `anchor` (at `at`) points: relative paths are relative to
    // anchor's folder, and inside a package ("a.usdz[b.usda]") to the folder in the package. A
    // variable expression (`...`) is evaluated first (expand).
    std::string resolve(const Layer& anchor, const std::string& written, const SourceLocation& at = {});
    // `text` itself, or what it evaluates to where it is a variable expression (variable_expression.h):
    // over the expressionVariables of the root layer, then those of `anchor` (the layer that writes
    // it; nullptr: the root's alone). One that cannot be evaluated is reported at `at` and taken as written.
    std::string expand(const Layer* anchor, const std::string& text, const SourceLocation& at);
    // Who asks for a layer: the arc ("sublayer", "reference", "payload"), the asset path as written,
    // where the arc is authored, and the prim it is authored on ("" for a sublayer).
    struct Request {
        std::string_view arc;
        std::string_view assetPath;
        const SourceLocation& where;
        std::string_view site;
    };
    // The layer at a resolved path, or null where it is missing or cannot be read (its syntax, a
    // package's): then the arc adds nothing, with a warning where it is authored that names the asset
    // and why (with the error's own file, line and column), once for each arc and asset.
    const Layer* open(const std::string& resolvedPath, const Request& request);
    const LayerStack& stackOf(const Layer& root);

private:
    using Loaded = std::variant<const Layer*, Error>;
    // A layer once read, or why it cannot be, each remembered by path.
    Loaded load(const std::string& resolvedPath);
    Loaded read(const std::string& resolvedPath, const std::string& key);
    Loaded add(std::string_view bytes, const std::string& identifier);
    // Registers a layer read under `key`, passing on its diagnostics.
    const Layer& keep(std::unique_ptr<Layer> layer, const std::string& key);
    void collect(const Layer& layer, const LayerOffset& toRoot, LayerStack& stack, std::vector<const Layer*>& including);

    DiagnosticSink& diagnostics_;
    ExpressionVariables rootVariables_;  // the root layer's expressionVariables
    std::map<std::string, std::unique_ptr<Layer>> layers_;  // by normalized absolute path
    std::map<std::string, Error> unreadable_;                // by normalized absolute path: why
    std::map<const Layer*, std::unique_ptr<LayerStack>> stacks_;
    assets::AssetReader assets_;  // the layers' files and packages, by absolute path
    std::map<std::string, const Layer*> packageRoots_;  // a package's path -> its root layer
};

}  // namespace obscura::usda
