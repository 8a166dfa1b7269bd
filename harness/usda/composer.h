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
    static std::variant<std::unique_ptr<Stage>, Error> compose(std::string_view rootText, const std::string& identifier,
                                                               const StageOptions& options);

    // A child prim's name and where its strongest spec is authored (blamed for its problems).
    struct ChildName {
        std::string name;
        SourceLocation where;
    };

private:
    explicit Composer(const StageOptions& options)
        : budget_(options.limits),
          variantFallbacks_(options.variantFallbacks),
          layers_(diagnostics_),
          indexer_(layers_, diagnostics_, budget_, variantFallbacks_) {}

    std::unique_ptr<Stage> composeStage(const Layer& rootLayer);
    // `parentIndex`: the parent's prim index, whose relocates move children away and in.
    void composeChildren(Stage& stage, Prim& parent, const IndexNode& parentIndex, const std::vector<ChildName>& authored);
    std::unique_ptr<Prim> composePrim(const std::string& path, const std::vector<Opinion>& opinions, Prim& parent);
    void reportBadMembershipExpressions(const Prim& prim);
    void expandAssetExpressions(Attribute& attribute);

    DiagnosticSink diagnostics_;
    CompositionBudget budget_;
    VariantFallbacks variantFallbacks_;
    LayerRegistry layers_;
    PrimIndexer indexer_;
    const LayerStack* rootStack_ = nullptr;
};

}  // namespace obscura::usda
