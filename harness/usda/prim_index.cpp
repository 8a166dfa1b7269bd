#include "harness/usda/prim_index.h"

#include <algorithm>

#include "harness/usda/instancing_key.h"
#include "harness/usda/sdf_path.h"

namespace obscura::usda {

namespace {

constexpr size_t kMaxArcNesting = 128;
constexpr int kMaxNamespaceDepth = 400;
// Variant selections can select further variants; bound the rounds in case they keep changing.
constexpr int kMaxVariantRounds = 64;

template <class F>
void forEachSpec(const IndexNode& node, F&& f) {
    for (const Layer* layer : node.stack->layers)
        if (const PrimSpec* spec = layer->find(node.site)) f(*spec, *layer);
}

// The specs that give the node's opinions: none for an inert node.
template <class F>
void forEachContributingSpec(const IndexNode& node, F&& f) {
    if (!node.inert) forEachSpec(node, f);
}

bool subtreeHasSpec(const IndexNode& node) {
    if (hasSpec(node)) return true;
    return std::any_of(node.children.begin(), node.children.end(), subtreeHasSpec);
}

void appendMappings(IndexNode& node, const PathMapping& arcMapping, const std::vector<PathMapping>& outer) {
    node.toRoot.push_back(arcMapping);
    node.toRoot.insert(node.toRoot.end(), outer.begin(), outer.end());
    for (IndexNode& child : node.children) appendMappings(child, arcMapping, outer);
}

// A grafted subtree's times go on through `outer` (the arc's offset, then the referring node's).
void prependTimeOffset(IndexNode& node, const LayerOffset& outer) {
    node.timeToRoot = outer.after(node.timeToRoot);
    for (IndexNode& child : node.children) prependTimeOffset(child, outer);
}

void sortChildren(IndexNode& node) {
    std::stable_sort(node.children.begin(), node.children.end(), [](const IndexNode& a, const IndexNode& b) {
        if (a.arc != b.arc) return a.arc < b.arc;
        return a.arcDepth > b.arcDepth;
    });
}

size_t nodeCount(const IndexNode& node) {
    size_t count = 1;
    for (const IndexNode& child : node.children) count += nodeCount(child);
    return count;
}

void collectOpinions(const IndexNode& node, std::vector<Opinion>& out) {
    forEachContributingSpec(node, [&](const PrimSpec& spec, const Layer& layer) {
        out.push_back(Opinion{&spec, &layer, &node, node.timeToRoot.after(node.stack->offsetOf(layer))});
    });
    for (const IndexNode& child : node.children) collectOpinions(child, out);
}

// A reference or payload with its asset path resolved, so that equal arcs written in different
// layers compare equal in list editing.
struct ResolvedReference {
    std::string layerPath;  // empty: internal
    std::string written;
    std::string primPath;
    SourceLocation where;
    LayerOffset authored;       // the arc's own layer offset
    const Layer* authoredIn;    // the layer that writes it
    bool operator==(const ResolvedReference& other) const {
        return layerPath == other.layerPath && primPath == other.primPath;
    }
};

}  // namespace

std::vector<Opinion> opinionsOf(const IndexNode& root) {
    std::vector<Opinion> out;
    collectOpinions(root, out);
    return out;
}

const Value* strongestMetadata(const IndexNode& root, const std::string& key) {
    const Value* found = nullptr;
    forEachContributingSpec(root, [&](const PrimSpec& spec, const Layer&) {
        if (found) return;
        if (const auto it = spec.metadata.find(key); it != spec.metadata.end()) found = &it->second;
    });
    for (auto child = root.children.begin(); !found && child != root.children.end(); ++child)
        found = strongestMetadata(*child, key);
    return found;
}

bool hasSpec(const IndexNode& node) {
    bool found = false;
    forEachSpec(node, [&](const PrimSpec&, const Layer&) { found = true; });
    return found;
}

std::string mapToRoot(const IndexNode& node, const std::string& path) {
    std::string mapped = path;
    for (const PathMapping& mapping : node.toRoot) mapped = sdfpath::replacePrefix(mapped, mapping.from, mapping.to);
    return mapped;
}

const IndexNode& PrimIndexer::index(const LayerStack& stack, const std::string& primPath,
                                    const SourceLocation& requestedAt) {
    const Key key{&stack, primPath};
    if (const auto it = memo_.find(key); it != memo_.end()) return it->second;
    if (inProgress_.count(key))
        throw CompositionFailure{Error{requestedAt, "composition cycle: <" + primPath + "> in '" +
                                                        stack.root().identifier + "' is reached from itself"}};
    if (inProgress_.size() >= kMaxArcNesting)
        throw CompositionFailure{Error{requestedAt, "composition arcs nested more than " +
                                                        std::to_string(kMaxArcNesting) + " deep"}};
    checkNamespaceDepth(primPath, requestedAt);
    inProgress_.insert(key);

    IndexNode root;
    const std::string parent = sdfpath::parentOf(primPath);
    if (parent == "/") {
        root.stack = &stack;
        root.site = primPath;
    } else {
        root = *mirror(index(stack, parent, requestedAt), sdfpath::nameOf(primPath), true, false);
    }
    build(root, primPath, requestedAt);

    inProgress_.erase(key);
    return memo_.emplace(key, std::move(root)).first->second;
}

// Pcp computes an instance proxy's index from its parent's with the nodes the instance's arcs did
// not bring marked inert (Pcp_ChildNodeIsInstanceable); further down they stay inert. Other prims'
// indexes are their sites' (index()), which arcs targeting those sites share.
const PrimIndexer::StagePrimIndex& PrimIndexer::stageIndex(const LayerStack& stack, const std::string& primPath,
                                                           const SourceLocation& requestedAt) {
    const Key key{&stack, primPath};
    if (const auto it = stagePrims_.find(key); it != stagePrims_.end()) return it->second;
    const std::string parent = sdfpath::parentOf(primPath);
    const StagePrimIndex* parentIndex = parent == "/" ? nullptr : &stageIndex(stack, parent, requestedAt);
    StagePrimIndex prim;
    if (parentIndex && (parentIndex->withinInstance || !parentIndex->instancingKey.empty())) {
        checkNamespaceDepth(primPath, requestedAt);
        IndexNode root = *mirror(*parentIndex->index, sdfpath::nameOf(primPath), true, !parentIndex->instancingKey.empty());
        build(root, primPath, requestedAt);
        prim.index = &withinInstances_.emplace(key, std::move(root)).first->second;
        prim.withinInstance = true;
    } else {
        prim.index = &index(stack, primPath, requestedAt);
    }
    prim.instancingKey = instancingKey(*prim.index);
    budget_.hold(sizeof(Key) + primPath.capacity() + sizeof(StagePrimIndex) + prim.instancingKey.capacity() + 32,
                 requestedAt);
    return stagePrims_.emplace(key, std::move(prim)).first->second;
}

void PrimIndexer::checkNamespaceDepth(const std::string& primPath, const SourceLocation& requestedAt) const {
    if (sdfpath::depthOf(primPath) > kMaxNamespaceDepth)
        throw CompositionFailure{Error{requestedAt, "prims nested more than " + std::to_string(kMaxNamespaceDepth) +
                                                        " deep under <" + sdfpath::parentOf(primPath) + ">"}};
}

void PrimIndexer::build(IndexNode& root, const std::string& primPath, const SourceLocation& requestedAt) {
    // The memo's entry: its key and map node.
    budget_.hold(heldBytes(root) + sizeof(Key) + primPath.capacity() + 32, requestedAt);
    budget_.beginIndex(primPath, nodeCount(root), requestedAt);
    std::vector<const IndexNode*> chain;
    expandArcs(root, chain);
    selectVariants(root);
    addImpliedClassArcs(root);
    moveSpecializesLast(root);
    budget_.endIndex();
}

void PrimIndexer::expandArcs(IndexNode& node, std::vector<const IndexNode*>& chain) {
    chain.push_back(&node);
    // Nodes carried over from the parent's index may have arcs authored at their new sites;
    // subtrees grafted below come complete from index().
    const size_t carried = node.children.size();
    for (size_t i = 0; i < carried; ++i) expandArcs(node.children[i], chain);

    if (node.inert) {
        chain.pop_back();
        return;
    }
    addRelocatedArcs(node);
    for (const Arc& arc : arcsAuthoredAt(node)) {
        checkCycle(arc, chain);
        const IndexNode& target = index(*arc.stack, arc.path, arc.where);
        if (!subtreeHasSpec(target)) {
            diagnostics_.warn(kindAt("unresolvedArc:" + arc.path, arc.where), arc.where,
                              "<" + arc.path + "> not found in '" + arc.stack->root().identifier + "'; arc ignored");
            continue;
        }
        graft(node, target, arc);
    }
    sortChildren(node);
    chain.pop_back();
}

std::optional<IndexNode> PrimIndexer::mirror(const IndexNode& node, const std::string& name, bool keepEmpty,
                                             bool ignored) {
    IndexNode out;
    out.stack = node.stack;
    out.site = sdfpath::appendChild(node.site, name);
    out.toRoot = node.toRoot;
    out.timeToRoot = node.timeToRoot;
    out.arc = node.arc;
    out.arcDepth = node.arcDepth;
    out.variantSet = node.variantSet;
    out.variant = node.variant;
    out.dueToAncestor = true;
    out.inert = node.inert || ignored;
    // Below a node the instance's arcs brought, everything is the instance's to share.
    for (const IndexNode& child : node.children)
        if (auto mirrored = mirror(child, name, false, ignored && child.dueToAncestor))
            out.children.push_back(std::move(*mirrored));
    if (!keepEmpty && out.children.empty() && !hasSpec(out) && !relocationsOf(*out.stack).count(out.site))
        return std::nullopt;
    return out;
}

const Relocations& PrimIndexer::relocationsOf(const LayerStack& stack) {
    const auto it = relocations_.find(&stack);
    if (it != relocations_.end()) return it->second;
    return relocations_.emplace(&stack, collectRelocates(stack, diagnostics_)).first->second;
}

void PrimIndexer::addRelocatedArcs(IndexNode& node) {
    const Relocations& relocations = relocationsOf(*node.stack);
    const auto relocation = relocations.find(node.site);
    if (relocation == relocations.end()) return;
    const std::string& source = relocation->second.source;
    const IndexNode& moved = index(*node.stack, source, relocation->second.where);
    budget_.addIndexNodes(nodeCount(moved) - 1, relocation->second.where);
    // The source's arcs map into the stack's namespace at the source; the relocation takes them
    // to the target, and the node's own mappings on to the indexed prim.
    for (const IndexNode& arc : moved.children) {
        IndexNode copy = arc;
        copy.dueToAncestor = false;
        appendMappings(copy, PathMapping{source, node.site}, node.toRoot);
        prependTimeOffset(copy, node.timeToRoot);
        budget_.hold(heldBytes(copy), relocation->second.where);
        node.children.push_back(std::move(copy));
    }
}

RelocatedChildren PrimIndexer::relocatedChildren(const IndexNode& root) {
    RelocatedChildren out;
    auto visit = [&](auto&& self, const IndexNode& node) -> void {
        if (!node.inert) {
            for (const auto& [target, relocation] : relocationsOf(*node.stack)) {
                if (sdfpath::parentOf(relocation.source) == node.site)
                    out.movedAway.insert(sdfpath::nameOf(relocation.source));
                if (sdfpath::parentOf(target) == node.site)
                    out.movedIn.emplace(sdfpath::nameOf(target), relocation.where);
            }
        }
        for (const IndexNode& child : node.children) self(self, child);
    };
    visit(visit, root);
    return out;
}

void PrimIndexer::graft(IndexNode& node, const IndexNode& target, const Arc& arc) {
    // Counted before the copy: a list naming one large prim many times must fail at the arc that
    // passes the limit, not after building every copy.
    budget_.addIndexNodes(nodeCount(target), arc.where);
    IndexNode graft = target;
    const std::string referringPath = sdfpath::stripVariants(node.site);
    appendMappings(graft, PathMapping{arc.path, referringPath}, node.toRoot);
    prependTimeOffset(graft, node.timeToRoot.after(arc.time));
    graft.arc = arc.type;
    graft.arcDepth = sdfpath::depthOf(referringPath);
    graft.dueToAncestor = false;
    budget_.hold(heldBytes(graft), arc.where);
    node.children.push_back(std::move(graft));
}

// Pcp's implied inherits and specializes: a class arc inside a referenced (or payloaded) layer
// stack is implied in the stack that refers to it, its path mapped into that namespace (paths
// outside the referenced prim map to themselves, as Pcp's reference mappings keep the root), so
// that a class of the referencing layers is stronger than everything the asset says. Children are
// done first, so arcs implied at an intermediate stack go on up to the root.
void PrimIndexer::addImpliedClassArcs(IndexNode& node) {
    for (IndexNode& child : node.children) addImpliedClassArcs(child);
    std::vector<Arc> implied;
    auto visit = [&](auto&& self, const IndexNode& parent, const IndexNode& child) -> void {
        if ((child.arc == ArcType::Inherit || child.arc == ArcType::Specialize) && !child.inert) {
            // The class's path in the namespace of `node`: through the mappings the authoring
            // node has beyond `node`'s own.
            std::string path = sdfpath::stripVariants(child.site);
            const size_t own = parent.toRoot.size() - node.toRoot.size();
            for (size_t i = 0; i < own; ++i)
                path = sdfpath::replacePrefix(path, parent.toRoot[i].from, parent.toRoot[i].to);
            implied.push_back(Arc{child.arc, node.stack, path, {}});
        }
        for (const IndexNode& grandchild : child.children) self(self, child, grandchild);
    };
    for (const IndexNode& child : node.children)
        if (child.stack != node.stack)
            for (const IndexNode& grandchild : child.children) visit(visit, child, grandchild);
    bool added = false;
    for (Arc& arc : implied) {
        const bool present = std::any_of(node.children.begin(), node.children.end(), [&](const IndexNode& c) {
            return c.stack == arc.stack && c.arc == arc.type && sdfpath::stripVariants(c.site) == arc.path;
        });
        if (present || sdfpath::hasPrefix(sdfpath::stripVariants(node.site), arc.path)) continue;
        arc.where = SourceLocation{arc.stack->root().identifier, 0, 0};
        const IndexNode& target = index(*arc.stack, arc.path, arc.where);
        if (!subtreeHasSpec(target)) continue;  // the referencing layers say nothing about the class
        graft(node, target, arc);
        added = true;
    }
    if (added) sortChildren(node);
}

// Specializes are the weakest arcs of the whole index (Pcp moves them under the root, after every
// other arc): a specialized prim's opinions only fill what nothing else in the index says. Nearer
// ones (implied into stronger layer stacks) stay stronger.
void PrimIndexer::moveSpecializesLast(IndexNode& root) {
    std::vector<IndexNode> moved;
    std::vector<IndexNode*> level = {&root};
    while (!level.empty()) {
        std::vector<IndexNode*> next;
        for (IndexNode* node : level) {
            for (auto it = node->children.begin(); it != node->children.end();) {
                if (it->arc == ArcType::Specialize && node != &root) {
                    moved.push_back(std::move(*it));
                    it = node->children.erase(it);
                } else {
                    ++it;
                }
            }
            for (IndexNode& child : node->children) next.push_back(&child);
        }
        level = std::move(next);
    }
    // Root's own specializes first (they are nearest), then those moved, in breadth-first order.
    std::stable_partition(root.children.begin(), root.children.end(),
                          [](const IndexNode& c) { return c.arc != ArcType::Specialize; });
    for (IndexNode& node : moved) root.children.push_back(std::move(node));
}

std::vector<PrimIndexer::Arc> PrimIndexer::arcsAuthoredAt(const IndexNode& node) {
    std::vector<ListOp<ResolvedReference>> references, payloads;
    std::vector<const ListOp<Reference>*> inherits, specializes;
    forEachSpec(node, [&](const PrimSpec& spec, const Layer& layer) {
        auto resolveIn = [&](const Reference& ref) {
            return ResolvedReference{ref.assetPath.empty() ? "" : layers_.resolve(layer, ref.assetPath, ref.where), ref.assetPath,
                                     ref.primPath, ref.where, ref.layerOffset, &layer};
        };
        references.push_back(spec.references.transformed(resolveIn));
        payloads.push_back(spec.payloads.transformed(resolveIn));
        inherits.push_back(&spec.inherits);
        specializes.push_back(&spec.specializes);
    });
    auto pointers = [](const std::vector<ListOp<ResolvedReference>>& ops) {
        std::vector<const ListOp<ResolvedReference>*> out;
        for (const auto& op : ops) out.push_back(&op);
        return out;
    };

    std::vector<Arc> arcs;
    for (const Reference& ref : composeListOps(inherits))
        arcs.push_back(Arc{ArcType::Inherit, node.stack, ref.primPath, ref.where});
    auto addReferences = [&](ArcType type, std::string_view name, const std::vector<ListOp<ResolvedReference>>& ops) {
        for (const ResolvedReference& ref : composeListOps(pointers(ops))) {
            // The offset as the authoring layer writes it, then that layer's place in its stack.
            const LayerOffset inStack = node.stack->offsetOf(*ref.authoredIn);
            if (ref.layerPath.empty()) {
                arcs.push_back(Arc{type, node.stack, ref.primPath, ref.where, inStack.after(ref.authored)});
                continue;
            }
            const Layer* layer =
                layers_.open(ref.layerPath, LayerRegistry::Request{name, ref.written, ref.where, node.site});
            if (!layer) continue;
            const std::optional<std::string> path =
                ref.primPath.empty() ? defaultPrimOf(*layer, ref.where) : ref.primPath;
            if (!path) continue;
            arcs.push_back(Arc{type, &layers_.stackOf(*layer), *path, ref.where,
                               inStack.after(arcTimeOffset(*ref.authoredIn, ref.authored, *layer))});
        }
    };
    addReferences(ArcType::Reference, "reference", references);
    addReferences(ArcType::Payload, "payload", payloads);
    for (const Reference& ref : composeListOps(specializes))
        arcs.push_back(Arc{ArcType::Specialize, node.stack, ref.primPath, ref.where});
    return arcs;
}

std::optional<std::string> PrimIndexer::defaultPrimOf(const Layer& layer, const SourceLocation& at) {
    if (const auto it = layer.metadata.find("defaultPrim"); it != layer.metadata.end() && !it->second.strings.empty()) {
        const std::string& name = it->second.strings.front();
        return name.starts_with("/") ? name : "/" + name;
    }
    if (layer.pseudoRoot.children.empty()) {
        // Pcp's PcpErrorUnresolvedPrimPath: the arc is ignored and the rest composed.
        diagnostics_.warn(kindAt("noPrimToReference:" + layer.identifier, at), at,
                          "layer '" + layer.identifier + "' has no prim to reference; arc ignored");
        return std::nullopt;
    }
    const std::string first = "/" + layer.pseudoRoot.children.front()->name;
    diagnostics_.warn("noDefaultPrim", at,
                      "layer '" + layer.identifier + "' has no defaultPrim; referencing its first root prim <" + first + ">");
    return first;
}

// Like Pcp: an arc may not target a site that is an ancestor or descendant of (or equal to) a
// site it is reached through in the same layer stack, or namespace would repeat forever.
void PrimIndexer::checkCycle(const Arc& arc, const std::vector<const IndexNode*>& chain) const {
    for (const IndexNode* node : chain) {
        if (node->stack != arc.stack) continue;
        const std::string site = sdfpath::stripVariants(node->site);
        if (sdfpath::hasPrefix(site, arc.path) || sdfpath::hasPrefix(arc.path, site))
            throw CompositionFailure{Error{arc.where, "composition cycle: <" + site + "> refers to <" + arc.path +
                                                          "> in '" + arc.stack->root().identifier + "'"}};
    }
}

void PrimIndexer::selectVariants(IndexNode& root) {
    for (int round = 0; round < kMaxVariantRounds; ++round) {
        std::vector<const IndexNode*> chain;
        if (!selectOneVariant(root, root, chain)) return;
    }
}

// Finds one variant set authored at a node whose selected variant is not (or no longer) in the
// index and fixes it; the selection is the strongest one anywhere in the prim's index.
bool PrimIndexer::selectOneVariant(const IndexNode& root, IndexNode& node, std::vector<const IndexNode*>& chain) {
    chain.push_back(&node);
    std::map<std::string, SourceLocation> sets;
    forEachContributingSpec(node, [&](const PrimSpec& spec, const Layer&) {
        for (const auto& entry : spec.variantSets) sets.emplace(entry.first, spec.where);
    });
    for (const auto& [set, where] : sets) {
        std::string selection;
        for (const Opinion& opinion : opinionsOf(root)) {
            const auto it = opinion.spec->variantSelections.find(set);
            if (it != opinion.spec->variantSelections.end()) {
                selection = layers_.expand(nullptr, it->second, opinion.spec->where);
                break;
            }
        }
        const std::string prefix = node.site + "{" + set + "=";
        const auto existing = std::find_if(node.children.begin(), node.children.end(), [&](const IndexNode& child) {
            return child.arc == ArcType::Variant && child.site == prefix + child.variant + "}";
        });
        if (existing != node.children.end() && existing->variant == selection) continue;

        IndexNode variant;
        variant.stack = node.stack;
        variant.toRoot = node.toRoot;
        variant.timeToRoot = node.timeToRoot;
        variant.arc = ArcType::Variant;
        variant.arcDepth = sdfpath::depthOf(sdfpath::stripVariants(node.site));
        variant.variantSet = set;
        auto choose = [&](const std::string& name) {
            variant.site = prefix + name + "}";
            variant.variant = name;
            return !name.empty() && hasSpec(variant);
        };
        bool found = choose(selection);
        // Without an authored selection, the first fallback the set has (Pcp's variant fallbacks).
        const auto fallbacks = variantFallbacks_.find(set);
        if (selection.empty() && fallbacks != variantFallbacks_.end())
            found = std::any_of(fallbacks->second.begin(), fallbacks->second.end(), choose);
        if (existing != node.children.end() && existing->variant == variant.variant && found) continue;
        if (selection.empty() && !found) {
            const std::string lacking = fallbacks == variantFallbacks_.end() ? "" : " and none of its fallbacks";
            diagnostics_.warn("noVariantSelection", where,
                              "variantSet \"" + set + "\" of <" + sdfpath::stripVariants(node.site) +
                                  "> has no selection" + lacking + "; its variants are ignored");
        } else if (!found) {
            diagnostics_.warn("missingVariant", where,
                              "variant \"" + selection + "\" not found in variantSet \"" + set + "\" of <" +
                                  sdfpath::stripVariants(node.site) + ">");
        }
        if (!found && existing == node.children.end()) continue;
        if (existing != node.children.end()) node.children.erase(existing);
        if (found) {
            budget_.addIndexNodes(1, where);
            budget_.hold(heldBytesOfNode(variant), where);
            expandArcs(variant, chain);
            node.children.push_back(std::move(variant));
            sortChildren(node);
        }
        return true;
    }
    for (IndexNode& child : node.children)
        if (selectOneVariant(root, child, chain)) return true;
    chain.pop_back();
    return false;
}

}  // namespace obscura::usda
