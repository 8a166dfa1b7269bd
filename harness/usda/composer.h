// Builds a Stage: opens the root layer stack, indexes every prim, and resolves each prim's
// opinions (strongest wins; list-edited fields compose from weakest to strongest).
#pragma once

#include <map>
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
    static std::variant<std::unique_ptr<Stage>, Error> compose(std::string_view rootText, const std::string& identifier,
                                                               const CompositionLimits& limits);

    // A child prim's name and where its strongest spec is authored (blamed for its problems).
    struct ChildName {
        std::string name;
        SourceLocation where;
    };

private:
    explicit Composer(const CompositionLimits& limits)
        : budget_(limits), layers_(diagnostics_), indexer_(layers_, diagnostics_, budget_) {}

    std::unique_ptr<Stage> composeStage(const Layer& rootLayer);
    void composeChildren(Stage& stage, Prim& parent, const std::vector<ChildName>& authored);
    std::unique_ptr<Prim> composePrim(const std::string& path, const std::vector<Opinion>& opinions, Prim& parent);

    DiagnosticSink diagnostics_;
    CompositionBudget budget_;
    LayerRegistry layers_;
    PrimIndexer indexer_;
    const LayerStack* rootStack_ = nullptr;
    // The root layer stack's relocates: target -> source, and where each is authored.
    std::map<std::string, std::string> sourcesByTarget_;
    std::map<std::string, SourceLocation> relocatedAt_;
    void collectRelocates(const std::map<std::string, Value>& metadata, const SourceLocation& where);
    void collectRelocates(const PrimSpec& spec);
};

}  // namespace obscura::usda
