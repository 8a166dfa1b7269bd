// Which specs, in which layers, give opinions about one composed prim, strongest first: a small
// version of USD's prim index (Pcp). Each node is a site (a prim path in a layer stack) reached
// through an arc; a node's arcs are its children, ordered inherits, variants, references,
// payloads, specializes (LIVRPS), and among arcs of one kind those authored deeper in namespace
// first. Class arcs (inherits, specializes) found inside another layer stack are also implied in
// the stack that refers to it, and specializes are moved after every other arc of the index. A
// prim's index starts from its parent's index (every node's site extended by the child name), so
// arcs authored on ancestors keep contributing to descendants.
//
// Descendants of an instance (usda/instancing_key.h) are instance proxies: they compose only what
// the instance's own arcs bring (Pcp marks every other node of their index inert), so opinions the
// referencing layer stack authors beneath an instance are ignored, as OpenUSD's scenegraph
// instancing specifies, and every instance of a prototype composes the same descendants.
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
#include "harness/usda/layer_stack_relocates.h"
#include "harness/usda/stage.h"

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
    LayerOffset timeToRoot;            // times of `stack`'s root layer -> the root layer stack's
    ArcType arc = ArcType::Root;
    int arcDepth = 0;                  // namespace depth of the prim the arc is authored on
    std::string variantSet, variant;   // the selection a Variant node stands for
    // Carried over from the parent prim's index rather than introduced by an arc authored at this
    // prim's sites (Pcp's IsDueToAncestor); an instance shares only what the others bring.
    bool dueToAncestor = false;
    // Within an instance, a node the instance's arcs did not bring: it keeps the graph's shape, but
    // its specs give no opinions, arcs, variant selections or relocates.
    bool inert = false;
    std::vector<IndexNode> children;
};

struct Opinion {
    const PrimSpec* spec;
    const Layer* layer;
    const IndexNode* node;
    LayerOffset time;  // the layer's times -> the stage's (its sublayer and arc offsets)
};

// Every spec of the index, strongest first (inert nodes give none).
std::vector<Opinion> opinionsOf(const IndexNode& root);
// The strongest opinion of the index about prim metadata `key`, or null.
const Value* strongestMetadata(const IndexNode& root, const std::string& key);
// Whether a layer of the node's layer stack has a spec at its site.
bool hasSpec(const IndexNode& node);
// A path authored in the node's layer stack, in the namespace of the prim the index is for.
std::string mapToRoot(const IndexNode& node, const std::string& path);

// Children of a prim that relocates in its index's layer stacks move away (sources) and in
// (targets, with where the relocate is authored). Names only: a node's site and the prim's path
// differ by a prefix, so a child keeps its name through the mapping.
struct RelocatedChildren {
    std::set<std::string> movedAway;
    std::map<std::string, SourceLocation> movedIn;
};

class PrimIndexer {
public:
    PrimIndexer(LayerRegistry& layers, DiagnosticSink& diagnostics, CompositionBudget& budget,
                const VariantFallbacks& variantFallbacks)
        : layers_(layers), diagnostics_(diagnostics), budget_(budget), variantFallbacks_(variantFallbacks) {}

    // The index of `primPath` in `stack` (memoized); `requestedAt` is blamed for cycles.
    const IndexNode& index(const LayerStack& stack, const std::string& primPath, const SourceLocation& requestedAt);

    // A prim of the stage whose root layer stack is `stack`: its index, which within an instance
    // holds only what the instance's arcs bring, and its instancing key ("" when it is no instance).
    struct StagePrimIndex {
        const IndexNode* index = nullptr;
        std::string instancingKey;
        bool withinInstance = false;  // a descendant of an instance: an instance proxy
    };
    // Memoized; a prim's parent is indexed first (the composer goes down the namespace).
    const StagePrimIndex& stageIndex(const LayerStack& stack, const std::string& primPath,
                                     const SourceLocation& requestedAt);
    // What relocates do to the children of the prim whose index is `root` (for the pseudo-root: a
    // node of the root layer stack at "/").
    RelocatedChildren relocatedChildren(const IndexNode& root);

private:
    struct Arc {
        ArcType type;
        const LayerStack* stack;
        std::string path;
        SourceLocation where;
        LayerOffset time{};  // the target stack's times -> the times of the stack authoring the arc
    };
    using Key = std::pair<const LayerStack*, std::string>;

    const Relocations& relocationsOf(const LayerStack& stack);
    void checkNamespaceDepth(const std::string& primPath, const SourceLocation& requestedAt) const;
    // Arcs, variants, implied classes and specializes of an index that starts as `root`.
    void build(IndexNode& root, const std::string& primPath, const SourceLocation& requestedAt);
    // The node's subtree as seen from child `name`: every site extended by the name. Nodes with
    // no spec there and nothing beneath are dropped (the root is always kept), unless a relocate
    // of their stack moves a prim to the site. `ignored`: the node brings nothing an instance's
    // descendants compose (the instance's root node, and nodes carried from its ancestors down to
    // the arcs authored at the instance), so its mirror is inert.
    std::optional<IndexNode> mirror(const IndexNode& node, const std::string& name, bool keepEmpty, bool ignored);
    // A relocation target's node gets what the source's arcs bring, mapped to the target (Pcp's
    // relocation arcs); the source's own opinions in the stack are not moved, as Pcp ignores them.
    void addRelocatedArcs(IndexNode& node);
    std::vector<Arc> arcsAuthoredAt(const IndexNode& node);
    // The prim a reference or payload without a prim path targets; nullopt (and a warning at `at`)
    // when the layer has none.
    std::optional<std::string> defaultPrimOf(const Layer& layer, const SourceLocation& at);
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
    const VariantFallbacks& variantFallbacks_;
    std::map<Key, IndexNode> memo_;
    std::map<Key, IndexNode> withinInstances_;  // indexes of instance proxies
    std::map<Key, StagePrimIndex> stagePrims_;
    std::map<const LayerStack*, Relocations> relocations_;
    std::set<Key> inProgress_;
};

}  // namespace obscura::usda
