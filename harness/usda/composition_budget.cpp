#include "harness/usda/composition_budget.h"

#include "harness/usda/diagnostics.h"
#include "harness/usda/prim_index.h"

#include <type_traits>

namespace obscura::usda {

namespace {

[[noreturn]] void fail(const SourceLocation& where, const std::string& message) {
    throw CompositionFailure{Error{where, "composition stopped: " + message}};
}

// libstdc++ keeps up to 15 characters inside the string object.
size_t heapOf(const std::string& text) { return text.capacity() > 15 ? text.capacity() + 1 : 0; }

// A red-black tree node of std::map: three pointers and a colour ahead of the value.
constexpr size_t kMapNodeOverhead = 32;
// A node of std::unordered_set<const void*> and its bucket: the next pointer, the key, a bucket.
constexpr size_t kHashNodeOverhead = 24;

// A payload of shared elements, the first time it is seen (its table entry included), else nothing.
template <class T>
size_t heapOfPayload(const SharedArray<T>& array, std::unordered_set<const void*>& counted) {
    if (!array.payload() || !counted.insert(array.payload()).second) return 0;
    size_t bytes = kHashNodeOverhead + array.payloadBytes();
    if constexpr (std::is_same_v<T, std::string>)
        for (const std::string& text : array) bytes += heapOf(text);
    return bytes;
}

// The heap behind a value (the Value object itself lives in its owner).
size_t heapOf(const Value& value, std::unordered_set<const void*>& counted) {
    return heapOf(value.typeName) + heapOfPayload(value.numbers, counted) + heapOfPayload(value.strings, counted);
}

size_t heldBytes(const Attribute& attribute, std::unordered_set<const void*>& counted) {
    size_t bytes = sizeof(Attribute) + kMapNodeOverhead + sizeof(std::string) + 2 * heapOf(attribute.name) + heapOf(attribute.typeName) +
                   heapOf(attribute.where.file);
    if (attribute.defaultValue) bytes += heapOf(*attribute.defaultValue, counted);
    for (const auto& [time, value] : attribute.timeSamples) bytes += kMapNodeOverhead + sizeof(value) + heapOf(value, counted);
    for (const auto& [key, value] : attribute.metadata)
        bytes += kMapNodeOverhead + sizeof(key) + heapOf(key) + sizeof(value) + heapOf(value, counted);
    if (attribute.connection) bytes += heapOf(*attribute.connection);
    // A spline is shared with its layer unless composition retimed it.
    if (attribute.spline && counted.insert(attribute.spline.get()).second)
        bytes += sizeof(Spline) + attribute.spline->knots.capacity() * sizeof(SplineKnot);
    return bytes;
}

}  // namespace

void CompositionBudget::addPrim(const std::string& path, const SourceLocation& where) {
    if (++prims_ > limits_.maxPrims)
        fail(where, "<" + path + "> would be prim " + std::to_string(prims_) + " of the stage; the limit is " +
                        std::to_string(limits_.maxPrims) + " prims");
}

void CompositionBudget::hold(size_t bytes, const SourceLocation& where) {
    bytes_ += bytes;
    if (bytes_ > limits_.maxMemoryBytes)
        fail(where, "the stage would hold more than " + std::to_string(limits_.maxMemoryBytes >> 20) +
                        " MiB (the memory limit) after " + std::to_string(prims_) + " prims");
}

void CompositionBudget::beginIndex(const std::string& primPath, size_t nodes, const SourceLocation& where) {
    indexes_.push_back(IndexInProgress{primPath, 0});
    addIndexNodes(nodes, where);
}

void CompositionBudget::addIndexNodes(size_t nodes, const SourceLocation& where) {
    IndexInProgress& index = indexes_.back();
    index.nodes += nodes;
    if (index.nodes > limits_.maxIndexNodes)
        fail(where, "more than " + std::to_string(limits_.maxIndexNodes) + " composition arcs contribute to <" +
                        index.primPath + "> (the limit of one prim's index)");
}

size_t heldBytesOfNode(const IndexNode& node) {
    size_t bytes = sizeof(IndexNode) + heapOf(node.site) + heapOf(node.variantSet) + heapOf(node.variant) +
                   node.toRoot.capacity() * sizeof(PathMapping) + node.children.capacity() * sizeof(IndexNode);
    for (const PathMapping& mapping : node.toRoot) bytes += heapOf(mapping.from) + heapOf(mapping.to);
    return bytes;
}

size_t heldBytes(const IndexNode& node) {
    size_t bytes = heldBytesOfNode(node);
    for (const IndexNode& child : node.children) bytes += heldBytes(child) - sizeof(IndexNode);
    return bytes;
}

void CompositionBudget::holdPrim(const Prim& prim, const SourceLocation& where) {
    // The prim, its entry in the stage's table by path (a hash node holding a copy of the path), and
    // its place in the parent's children.
    size_t bytes = sizeof(Prim) + 2 * heapOf(prim.path) + kMapNodeOverhead + sizeof(std::string) + sizeof(void*) +
                   heapOf(prim.name) + heapOf(prim.typeName) + heapOf(prim.kind) + heapOf(prim.instancingKey) +
                   heapOf(prim.where.file);
    for (const auto& [name, attribute] : prim.attributes) bytes += heldBytes(attribute, countedPayloads_);
    for (const auto& [name, relationship] : prim.relationships) {
        bytes += sizeof(Relationship) + kMapNodeOverhead + heapOf(relationship.name) +
                 relationship.targets.capacity() * sizeof(std::string);
        for (const std::string& target : relationship.targets) bytes += heapOf(target);
    }
    for (const auto& [key, value] : prim.metadata)
        bytes += kMapNodeOverhead + sizeof(key) + heapOf(key) + sizeof(value) + heapOf(value, countedPayloads_);
    for (const std::string& schema : prim.apiSchemas) bytes += sizeof(std::string) + heapOf(schema);
    hold(bytes, where);
}

}  // namespace obscura::usda
