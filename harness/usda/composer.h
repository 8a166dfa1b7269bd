// Builds a Stage: opens the root layer stack, indexes every prim, and resolves each prim's
// opinions (strongest wins; list-edited fields compose from weakest to strongest).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "harness/usda/diagnostics.h"
#include "harness/usda/layer_registry.h"
#include "harness/usda/prim_index.h"
#include "harness/usda/stage.h"

namespace obscura::usda {

class Composer {
public:
    static std::variant<std::unique_ptr<Stage>, Error> compose(std::string_view rootText, const std::string& identifier);

private:
    Composer() : layers_(diagnostics_), indexer_(layers_, diagnostics_) {}

    std::unique_ptr<Stage> composeStage(const Layer& rootLayer);
    void composeChildren(Stage& stage, Prim& parent, const std::vector<std::string>& names);
    std::unique_ptr<Prim> composePrim(const std::string& path, const std::vector<Opinion>& opinions, Prim& parent);

    DiagnosticSink diagnostics_;
    LayerRegistry layers_;
    PrimIndexer indexer_;
    const LayerStack* rootStack_ = nullptr;
};

}  // namespace obscura::usda
