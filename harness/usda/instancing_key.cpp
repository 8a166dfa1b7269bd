#include "harness/usda/instancing_key.h"

namespace obscura::usda {

namespace {

// Each node as its arc, its layer stack (by root layer) and its site, which carries the variant
// selections made along the way ("/Asset{lod=high}"); nesting by brackets, so that two indexes
// with the same nodes in other places differ.
void appendArcs(const IndexNode& node, std::string& key) {
    for (const IndexNode& child : node.children) {
        key += std::to_string(int(child.arc));
        key += ' ';
        key += child.stack->root().identifier;
        key += ' ';
        key += child.site;
        key += '[';
        appendArcs(child, key);
        key += ']';
    }
}

}  // namespace

std::string instancingKey(const IndexNode& root) {
    std::string key;
    appendArcs(root, key);
    return key;
}

}  // namespace obscura::usda
