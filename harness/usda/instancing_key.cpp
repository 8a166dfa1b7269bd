#include "harness/usda/instancing_key.h"

namespace obscura::usda {

namespace {

// Each node the instance shares as its arc, its layer stack (by root layer) and its site, which
// carries the variant selections made along the way ("/Asset{lod=high}"); nesting by brackets, so
// that two indexes with the same nodes in other places differ. A node is the instance's when its
// arc is authored at the prim's sites, or it lies below such a node (`shared`).
void appendArcs(const IndexNode& node, bool shared, std::string& key, bool& bringsSpecs) {
    for (const IndexNode& child : node.children) {
        const bool instances = shared || !child.dueToAncestor;
        if (!instances) {
            appendArcs(child, false, key, bringsSpecs);
            continue;
        }
        bringsSpecs = bringsSpecs || hasSpec(child);
        key += std::to_string(int(child.arc));
        key += ' ';
        key += child.stack->root().identifier;
        key += ' ';
        key += child.site;
        key += '[';
        appendArcs(child, true, key, bringsSpecs);
        key += ']';
    }
}

}  // namespace

std::string instancingKey(const IndexNode& root) {
    const Value* instanceable = strongestMetadata(root, "instanceable");
    if (!instanceable || instanceable->numbers.empty() || instanceable->numbers.front() == 0.0) return {};
    std::string key;
    bool bringsSpecs = false;
    appendArcs(root, false, key, bringsSpecs);
    return bringsSpecs ? key : std::string();
}

}  // namespace obscura::usda
