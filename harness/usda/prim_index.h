// Which specs, in which layers, give opinions about one composed prim, strongest first: a small
// version of USD's prim index (Pcp). Each node is a site (a prim path in a layer stack) reached
// through an arc; a node's arcs are its children, ordered inherits, variants, references,
// payloads, specializes (LIVRPS), and among arcs of one kind those authored deeper in namespace
// first. Class arcs (inherits, specializes) found inside another layer stack are also implied in
// the stack that refers to it, and specializes are moved after every other arc of the index. A
// prim's index starts from its parent's index (every node's site extended by the child name), so
// arcs authored on ancestors keep contributing to descendants.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "harness/usda/composition_budget.h"
#include "harness/usda/diagnostics.h"
#include "harness/usda/layer_registry.h"

namespace obscura::usda {

enum class ArcType { Root, Inherit, Variant, Reference, Payload, Specialize };

// A prefix substitution taking paths of an arc's target into the namespace that refers to it.
struct PathMapping {
    std::string from;
    std::string to;
};

struct IndexNode {
    const LayerStack* stack = nullptr;
    std::string site;                  // prim path in `stack`, variant selections included: /A{lod=hi}/B
    std::vector<PathMapping> toRoot;   // applied in order: `stack` paths -> the indexed prim's namespace
    ArcType arc = ArcType::Root;
    int arcDepth = 0;                  // namespace depth of the prim the arc is authored on
    std::string variantSet, variant;   // the selection a Variant node stands for
    std::vector<IndexNode> children;
};

struct Opinion {
    const PrimSpec* spec;
    const Layer* layer;
    const IndexNode* node;
};

// Every spec of the index, strongest first.
std::vector<Opinion> opinionsOf(const IndexNode& root);
// A path authored in the node's layer stack, in the namespace of the prim the index is for.
std::string mapToRoot(const IndexNode& node, const std::string& path);

class PrimIndexer {
public:
    PrimIndexer(LayerRegistry& layers, DiagnosticSink& diagnostics, CompositionBudget& budget)
        : layers_(layers), diagnostics_(diagnostics), budget_(budget) {}

    // The index of `primPath` in `stack` (memoized); `requestedAt` is blamed for cycles.
    const IndexNode& index(const LayerStack& stack, const std::string& primPath, const SourceLocation& requestedAt);
    // Relocates of `stack` (the stage's root layer stack), target path -> source path: a target's
    // index holds what its source's arcs bring, mapped to the target (Pcp's relocation arcs).
    void setRelocations(const LayerStack& stack, std::map<std::string, std::string> sourcesByTarget) {
        relocationStack_ = &stack;
        sourcesByTarget_ = std::move(sourcesByTarget);
    }

private:
    struct Arc {
        ArcType type;
        const LayerStack* stack;
        std::string path;
        SourceLocation where;
    };
    using Key = std::pair<const LayerStack*, std::string>;

    std::vector<Arc> arcsAuthoredAt(const IndexNode& node);
    std::string defaultPrimOf(const Layer& layer, const SourceLocation& at);
    void expandArcs(IndexNode& node, std::vector<const IndexNode*>& chain);
    // `target`'s index as a child of `node`, reached through `arc`.
    void graft(IndexNode& node, const IndexNode& target, const Arc& arc);
    void addImpliedClassArcs(IndexNode& node);
    void moveSpecializesLast(IndexNode& root);
    void checkCycle(const Arc& arc, const std::vector<const IndexNode*>& chain) const;
    void selectVariants(IndexNode& root);
    bool selectOneVariant(const IndexNode& root, IndexNode& node, std::vector<const IndexNode*>& chain);

    LayerRegistry& layers_;
    DiagnosticSink& diagnostics_;
    CompositionBudget& budget_;
    std::map<Key, IndexNode> memo_;
    const LayerStack* relocationStack_ = nullptr;
    std::map<std::string, std::string> sourcesByTarget_;
    std::set<Key> inProgress_;
};

}  // namespace obscura::usda
