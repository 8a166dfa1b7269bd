// Field values of a crate file (ValueReps) decoded into the layer model's types, following
// OpenUSD's reader (pxr/usd/sdf/crateFile.cpp, crateValueInliners.h): small values inlined in
// the rep (doubles as floats, vectors and diagonal matrices as int8 components), others at the
// rep's offset; arrays with a length prefix, integer and float arrays possibly compressed.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/usda/crate_file.h"
#include "harness/usda/layer.h"

namespace obscura::usda::crate {

// IEEE 754 binary16 to double.
double halfToDouble(uint16_t bits);

class ValueReader {
public:
    explicit ValueReader(const File& file) : file_(file) {}

    // Numbers, strings, tokens, asset paths and paths, their arrays and vectors, and blocks
    // (None); nullopt for a type that is no plain value (list ops, dictionaries, ...).
    std::optional<Value> value(ValueRep rep);
    // Token, string and path list ops (paths as absolute text).
    ListOp<std::string> nameListOp(ValueRep rep);
    // References, payloads (a list op or a single payload), with their layer offsets.
    ListOp<Reference> arcListOp(ValueRep rep, const SourceLocation& where);
    // The pseudo-root's subLayerOffsets: one per sublayer, in order.
    std::vector<LayerOffset> layerOffsets(ValueRep rep);
    // Dictionary entries flattened into `out` as "prefix" + "key:subkey".
    void dictionary(ValueRep rep, const std::string& prefix, std::map<std::string, Value>& out);
    std::map<std::string, std::string> variantSelections(ValueRep rep);
    std::map<double, Value> timeSamples(ValueRep rep);
    // A token or string vector.
    std::vector<std::string> names(ValueRep rep);
    // An enum stored in the rep (specifier, variability, permission).
    uint32_t enumValue(ValueRep rep) const { return static_cast<uint32_t>(rep.payload()); }

private:
    void readDictionary(ByteReader& reader, const std::string& prefix, std::map<std::string, Value>& out, int depth);
    std::optional<Value> value(ValueRep rep, int depth);
    Value readArray(ValueRep rep, uint64_t at);
    std::vector<std::string> readNames(ByteReader& reader, Type element);
    Reference readArc(ByteReader& reader, bool isPayload, const SourceLocation& where);
    // Counts decoded elements against the budget below.
    void spend(uint64_t elements, uint64_t at);

    const File& file_;
    // Values may be shared (time samples naming one array, dictionaries naming one dictionary), so
    // a small file can describe far more data than it holds; decoding stops at this many numbers,
    // strings and dictionary entries for one layer (2 GB of numbers, CompositionLimits' share).
    static constexpr uint64_t kMaxDecodedElements = uint64_t(1) << 28;
    uint64_t decoded_ = 0;
};

}  // namespace obscura::usda::crate
