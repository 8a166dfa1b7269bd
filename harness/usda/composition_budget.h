// Counts what composition builds against CompositionLimits and fails the moment a limit is
// passed, naming where in the scene the growth came from.
#pragma once

#include <string>
#include <unordered_set>
#include <vector>

#include "harness/usda/stage.h"

namespace obscura::usda {

struct IndexNode;

class CompositionBudget {
public:
    explicit CompositionBudget(const CompositionLimits& limits) : limits_(limits) {}

    // One more prim on the stage, authored at `where`.
    void addPrim(const std::string& path, const SourceLocation& where);
    // Memory now held by composition (a copied index subtree), blamed on `where`.
    void hold(size_t bytes, const SourceLocation& where);
    // A composed prim without its children, blamed on `where`. The elements of its values are
    // shared with its layers and with the other prims that compose the same specs: each payload
    // is counted the first time a prim holds it.
    void holdPrim(const Prim& prim, const SourceLocation& where);

    // The index of `primPath` is being built; nodes are added to the innermost one.
    void beginIndex(const std::string& primPath, size_t nodes, const SourceLocation& where);
    void endIndex() { indexes_.pop_back(); }
    void addIndexNodes(size_t nodes, const SourceLocation& where);

private:
    struct IndexInProgress {
        std::string primPath;
        size_t nodes;
    };
    CompositionLimits limits_;
    size_t prims_ = 0;
    size_t bytes_ = 0;
    std::vector<IndexInProgress> indexes_;
    std::unordered_set<const void*> countedPayloads_;
};

// Estimates of the heap a structure holds (its own size, strings beyond the small-string buffer,
// vectors' capacity), close enough to bound memory: within a few tens of percent of the
// allocator's count on the scenes of the tests.
size_t heldBytes(const IndexNode& node);       // the node and its subtree
size_t heldBytesOfNode(const IndexNode& node);  // the node alone

}  // namespace obscura::usda
