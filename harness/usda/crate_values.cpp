#include "harness/usda/crate_values.h"

#include <array>
#include <cmath>

namespace obscura::usda::crate {

namespace {

// Dictionaries inside dictionaries deeper than this are corrupt (or hostile) data.
constexpr int kMaxNesting = 64;
// Arrays shorter than this are stored uncompressed even when flagged compressed.
constexpr uint64_t kMinCompressedArraySize = 16;

enum class Component { Bool, UChar, Int, UInt, Int64, UInt64, Half, Float, Double, Token, String, Asset };

struct TypeInfo {
    Type type;
    const char* name;  // as in .usda
    Component component;
    int count;         // components per element
    bool quaternion;   // stored (i, j, k, real); the layer model writes the real part first
    bool matrix;
};

constexpr std::array kTypes = {
    TypeInfo{Type::Bool, "bool", Component::Bool, 1, false, false},
    TypeInfo{Type::UChar, "uchar", Component::UChar, 1, false, false},
    TypeInfo{Type::Int, "int", Component::Int, 1, false, false},
    TypeInfo{Type::UInt, "uint", Component::UInt, 1, false, false},
    TypeInfo{Type::Int64, "int64", Component::Int64, 1, false, false},
    TypeInfo{Type::UInt64, "uint64", Component::UInt64, 1, false, false},
    TypeInfo{Type::Half, "half", Component::Half, 1, false, false},
    TypeInfo{Type::Float, "float", Component::Float, 1, false, false},
    TypeInfo{Type::Double, "double", Component::Double, 1, false, false},
    TypeInfo{Type::TimeCode, "timecode", Component::Double, 1, false, false},
    TypeInfo{Type::String, "string", Component::String, 1, false, false},
    TypeInfo{Type::PathExpression, "string", Component::String, 1, false, false},
    TypeInfo{Type::Token, "token", Component::Token, 1, false, false},
    TypeInfo{Type::AssetPath, "asset", Component::Asset, 1, false, false},
    TypeInfo{Type::Matrix2d, "matrix2d", Component::Double, 4, false, true},
    TypeInfo{Type::Matrix3d, "matrix3d", Component::Double, 9, false, true},
    TypeInfo{Type::Matrix4d, "matrix4d", Component::Double, 16, false, true},
    TypeInfo{Type::Quatd, "quatd", Component::Double, 4, true, false},
    TypeInfo{Type::Quatf, "quatf", Component::Float, 4, true, false},
    TypeInfo{Type::Quath, "quath", Component::Half, 4, true, false},
    TypeInfo{Type::Vec2d, "double2", Component::Double, 2, false, false},
    TypeInfo{Type::Vec2f, "float2", Component::Float, 2, false, false},
    TypeInfo{Type::Vec2h, "half2", Component::Half, 2, false, false},
    TypeInfo{Type::Vec2i, "int2", Component::Int, 2, false, false},
    TypeInfo{Type::Vec3d, "double3", Component::Double, 3, false, false},
    TypeInfo{Type::Vec3f, "float3", Component::Float, 3, false, false},
    TypeInfo{Type::Vec3h, "half3", Component::Half, 3, false, false},
    TypeInfo{Type::Vec3i, "int3", Component::Int, 3, false, false},
    TypeInfo{Type::Vec4d, "double4", Component::Double, 4, false, false},
    TypeInfo{Type::Vec4f, "float4", Component::Float, 4, false, false},
    TypeInfo{Type::Vec4h, "half4", Component::Half, 4, false, false},
    TypeInfo{Type::Vec4i, "int4", Component::Int, 4, false, false},
};

const TypeInfo* typeInfo(Type type) {
    for (const TypeInfo& info : kTypes)
        if (info.type == type) return &info;
    return nullptr;
}

size_t componentBytes(Component component) {
    switch (component) {
    case Component::Bool:
    case Component::UChar: return 1;
    case Component::Half: return 2;
    case Component::Int64:
    case Component::UInt64:
    case Component::Double: return 8;
    default: return 4;
    }
}

template <class T>
T load(const char* p) {
    T value;
    std::memcpy(&value, p, sizeof(T));
    return value;
}

double componentValue(Component component, const char* p) {
    switch (component) {
    case Component::Bool: return load<uint8_t>(p) ? 1.0 : 0.0;
    case Component::UChar: return load<uint8_t>(p);
    case Component::Int: return load<int32_t>(p);
    case Component::UInt: return load<uint32_t>(p);
    case Component::Int64: return static_cast<double>(load<int64_t>(p));
    case Component::UInt64: return static_cast<double>(load<uint64_t>(p));
    case Component::Half: return halfToDouble(load<uint16_t>(p));
    case Component::Float: return load<float>(p);
    default: return load<double>(p);
    }
}

bool isStringLike(Component component) {
    return component == Component::Token || component == Component::String || component == Component::Asset;
}

Value emptyValue(const TypeInfo& info, bool isArray) {
    Value value;
    value.typeName = info.name;
    value.isArray = isArray;
    value.tupleSize = info.count;
    return value;
}

// Appends elements read as raw little-endian components, moving quaternions' real part first.
void appendElements(Value& out, const TypeInfo& info, std::span<const char> bytes, uint64_t elements) {
    const size_t size = componentBytes(info.component);
    std::vector<double>& numbers = out.numbers.edit();
    numbers.reserve(numbers.size() + elements * static_cast<uint64_t>(info.count));
    for (uint64_t e = 0; e < elements; ++e) {
        const char* element = bytes.data() + e * size * static_cast<uint64_t>(info.count);
        if (info.quaternion) {
            numbers.push_back(componentValue(info.component, element + 3 * size));
            for (int c = 0; c < 3; ++c) numbers.push_back(componentValue(info.component, element + c * size));
        } else {
            for (int c = 0; c < info.count; ++c) numbers.push_back(componentValue(info.component, element + c * size));
        }
    }
}

}  // namespace

double halfToDouble(uint16_t bits) {
    const int sign = bits >> 15, exponent = (bits >> 10) & 0x1F, mantissa = bits & 0x3FF;
    double magnitude;
    if (exponent == 0) {
        magnitude = std::ldexp(mantissa, -24);
    } else if (exponent == 31) {
        magnitude = mantissa ? std::nan("") : INFINITY;
    } else {
        magnitude = std::ldexp(mantissa + 1024, exponent - 25);
    }
    return sign ? -magnitude : magnitude;
}

void ValueReader::spend(uint64_t elements, uint64_t at) {
    decoded_ += elements;
    if (decoded_ > kMaxDecodedElements)
        throw Failure{at, "the file's values decode to more than " + std::to_string(kMaxDecodedElements) +
                              " elements (shared values repeated without bound?)"};
}

std::optional<Value> ValueReader::value(ValueRep rep) { return value(rep, 0); }

std::optional<Value> ValueReader::value(ValueRep rep, int depth) {
    if (depth > kMaxNesting) throw Failure{rep.payload(), "values nested deeper than " + std::to_string(kMaxNesting)};
    const uint64_t at = rep.payload();
    if (rep.type() == Type::ValueBlock) {
        Value blocked;
        blocked.blocked = true;
        return blocked;
    }
    if (rep.type() == Type::TokenVector || rep.type() == Type::StringVector || rep.type() == Type::PathVector) {
        Value value;
        value.typeName = rep.type() == Type::PathVector ? "path" : rep.type() == Type::TokenVector ? "token" : "string";
        value.isArray = true;
        value.strings = names(rep);
        return value;
    }
    if (rep.type() == Type::Relocates) {
        // Source and target path indexes in pairs, as the text reader keeps relocates.
        ByteReader reader(file_.bytes(), at);
        const uint64_t count = reader.read<uint64_t>();
        if (count > reader.size() / 8) throw Failure{at, "relocates of " + std::to_string(count) + " pairs"};
        spend(count, at);
        Value value;
        value.typeName = "relocates";
        std::vector<std::string>& paths = value.strings.edit();
        for (uint64_t i = 0; i < 2 * count; ++i) paths.push_back(file_.pathText(reader.read<uint32_t>(), at));
        return value;
    }
    if (rep.type() == Type::DoubleVector) {
        ByteReader reader(file_.bytes(), at);
        const uint64_t count = reader.read<uint64_t>();
        if (count > reader.size() / 8) throw Failure{at, "double vector of " + std::to_string(count) + " elements"};
        spend(count, at);
        Value value = emptyValue(*typeInfo(Type::Double), true);
        appendElements(value, *typeInfo(Type::Double), reader.take(count * 8), count);
        return value;
    }
    const TypeInfo* info = typeInfo(rep.type());
    if (!info) return std::nullopt;
    if (rep.isArray()) return readArray(rep, at);

    Value value = emptyValue(*info, false);
    const auto inlined = static_cast<uint32_t>(rep.payload());
    if (isStringLike(info->component)) {
        value.strings.edit().push_back(info->component == Component::String ? file_.string(inlined, at)
                                                                     : file_.token(inlined, at));
        return value;
    }
    if (rep.isInlined()) {
        char bytes[4];
        std::memcpy(bytes, &inlined, sizeof(bytes));
        if (info->matrix) {
            // Diagonal matrices with int8 entries: the diagonal.
            const int rows = info->count == 16 ? 4 : info->count == 9 ? 3 : 2;
            for (int r = 0; r < rows; ++r)
                for (int c = 0; c < rows; ++c) value.numbers.edit().push_back(r == c ? static_cast<int8_t>(bytes[r]) : 0.0);
        } else if (info->count > 1) {
            // Vectors whose components are all int8.
            for (int c = 0; c < info->count; ++c) value.numbers.edit().push_back(static_cast<int8_t>(bytes[c]));
        } else if (info->component == Component::Double) {
            value.numbers.edit().push_back(load<float>(bytes));  // doubles exactly representable as floats
        } else if (info->component == Component::Int64) {
            value.numbers.edit().push_back(load<int32_t>(bytes));
        } else if (info->component == Component::UInt64) {
            value.numbers.edit().push_back(load<uint32_t>(bytes));
        } else {
            value.numbers.edit().push_back(componentValue(info->component, bytes));
        }
        return value;
    }
    ByteReader reader(file_.bytes(), at);
    appendElements(value, *info, reader.take(componentBytes(info->component) * static_cast<uint64_t>(info->count)), 1);
    return value;
}

Value ValueReader::readArray(ValueRep rep, uint64_t at) {
    const TypeInfo& info = *typeInfo(rep.type());
    Value value = emptyValue(info, true);
    if (rep.payload() == 0) return value;
    ByteReader reader(file_.bytes(), at);
    const Version& version = file_.version();
    if (!version.atLeast(0, 5)) reader.read<uint32_t>();  // rank, always 1
    const uint64_t count = version.atLeast(0, 7) ? reader.read<uint64_t>() : reader.read<uint32_t>();
    spend(count, at);
    const uint64_t elementBytes = componentBytes(info.component) * static_cast<uint64_t>(info.count);
    auto raw = [&] {
        if (count > reader.size() / elementBytes)
            throw Failure{at, "array of " + std::to_string(count) + " elements cannot fit in the file"};
        const auto bytes = reader.take(count * elementBytes);
        if (isStringLike(info.component)) {
            std::vector<std::string>& strings = value.strings.edit();
            strings.reserve(count);
            for (uint64_t i = 0; i < count; ++i) {
                const uint32_t index = load<uint32_t>(bytes.data() + i * 4);
                strings.push_back(info.component == Component::String ? file_.string(index, at) : file_.token(index, at));
            }
        } else {
            appendElements(value, info, bytes, count);
        }
    };
    auto compressedBlock = [&] {
        const uint64_t blockAt = reader.tell();
        const uint64_t size = reader.read<uint64_t>();
        return std::pair{reader.take(size), blockAt + 8};
    };
    const bool integral = info.count == 1 && (info.component == Component::Int || info.component == Component::UInt ||
                                              info.component == Component::Int64 || info.component == Component::UInt64);
    const bool floating = info.count == 1 && rep.type() != Type::TimeCode &&
                          (info.component == Component::Half || info.component == Component::Float ||
                           info.component == Component::Double);
    if (!rep.isCompressed() || count < kMinCompressedArraySize || (!integral && !floating)) {
        raw();
        return value;
    }
    std::vector<double>& numbers = value.numbers.edit();
    numbers.reserve(count);
    if (integral) {
        const auto [block, blockAt] = compressedBlock();
        if (info.component == Component::Int64 || info.component == Component::UInt64) {
            for (int64_t x : decompressIntegers<int64_t>(block, count, blockAt))
                numbers.push_back(info.component == Component::Int64 ? static_cast<double>(x)
                                                                     : static_cast<double>(static_cast<uint64_t>(x)));
        } else {
            for (int32_t x : decompressIntegers<int32_t>(block, count, blockAt))
                numbers.push_back(info.component == Component::Int ? x : static_cast<double>(static_cast<uint32_t>(x)));
        }
        return value;
    }
    // Floating-point arrays: 'i' integers stored as coded int32, or 't' a lookup table and coded indexes.
    const uint64_t codeAt = reader.tell();
    const char code = reader.read<char>();
    if (code == 'i') {
        const auto [block, blockAt] = compressedBlock();
        for (int32_t x : decompressIntegers<int32_t>(block, count, blockAt)) numbers.push_back(x);
    } else if (code == 't') {
        const uint32_t tableSize = reader.read<uint32_t>();
        if (tableSize > reader.size() / elementBytes) throw Failure{codeAt + 1, "lookup table cannot fit in the file"};
        Value table = emptyValue(info, true);
        appendElements(table, info, reader.take(tableSize * elementBytes), tableSize);
        const auto [block, blockAt] = compressedBlock();
        for (uint32_t index : decompressIntegers<uint32_t>(block, count, blockAt)) {
            if (index >= tableSize)
                throw Failure{blockAt, "lookup index " + std::to_string(index) + " of " + std::to_string(tableSize)};
            numbers.push_back(table.numbers[index]);
        }
    } else {
        throw Failure{codeAt, "unknown float array coding '" + std::string(1, code) + "'"};
    }
    return value;
}

std::vector<std::string> ValueReader::readNames(ByteReader& reader, Type element) {
    const uint64_t at = reader.tell();
    const uint64_t count = reader.read<uint64_t>();
    if (count > reader.size() / 4) throw Failure{at, "list of " + std::to_string(count) + " names cannot fit in the file"};
    spend(count, at);
    std::vector<std::string> out;
    out.reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
        const uint32_t index = reader.read<uint32_t>();
        out.push_back(element == Type::Token    ? file_.token(index, at)
                      : element == Type::String ? file_.string(index, at)
                                                : file_.path(index, at).text);
    }
    return out;
}

std::vector<std::string> ValueReader::names(ValueRep rep) {
    ByteReader reader(file_.bytes(), rep.payload());
    const Type element = rep.type() == Type::TokenVector ? Type::Token : rep.type() == Type::StringVector ? Type::String
                                                                                                          : Type::PathVector;
    return readNames(reader, element);
}

namespace {

// SdfListOp header bits, and the order the item lists follow it in.
constexpr uint8_t kIsExplicit = 1;
struct ListBit {
    uint8_t bit;
    ListOpKind kind;
};
constexpr std::array kListBits = {ListBit{2, ListOpKind::Explicit}, ListBit{4, ListOpKind::Add},
                                  ListBit{32, ListOpKind::Prepend}, ListBit{64, ListOpKind::Append},
                                  ListBit{8, ListOpKind::Delete},   ListBit{16, ListOpKind::Reorder}};

template <class T, class ReadList>
ListOp<T> readListOp(ByteReader& reader, ReadList readList) {
    ListOp<T> op;
    const auto header = reader.read<uint8_t>();
    if (header & kIsExplicit) op.set(ListOpKind::Explicit, {});
    for (const ListBit& list : kListBits)
        if (header & list.bit) op.set(list.kind, readList());
    return op;
}

}  // namespace

ListOp<std::string> ValueReader::nameListOp(ValueRep rep) {
    const Type element = rep.type() == Type::TokenListOp ? Type::Token : rep.type() == Type::StringListOp ? Type::String
                                                                                                          : Type::PathVector;
    if (rep.type() != Type::TokenListOp && rep.type() != Type::StringListOp && rep.type() != Type::PathListOp)
        throw Failure{rep.payload(), "expected a token, string or path list op, found type " +
                                         std::to_string(static_cast<int>(rep.type()))};
    ByteReader reader(file_.bytes(), rep.payload());
    return readListOp<std::string>(reader, [&] { return readNames(reader, element); });
}

Reference ValueReader::readArc(ByteReader& reader, bool isPayload, const SourceLocation& where) {
    const uint64_t at = reader.tell();
    Reference arc;
    arc.where = where;
    arc.assetPath = file_.string(reader.read<uint32_t>(), at);
    arc.primPath = file_.pathText(reader.read<uint32_t>(), at);
    if (!isPayload || file_.version().atLeast(0, 8)) {
        arc.layerOffset.offset = reader.read<double>();
        arc.layerOffset.scale = reader.read<double>();
    }
    if (!isPayload) {
        std::map<std::string, Value> customData;  // not used by composition
        readDictionary(reader, "", customData, 0);
    }
    return arc;
}

ListOp<Reference> ValueReader::arcListOp(ValueRep rep, const SourceLocation& where) {
    ByteReader reader(file_.bytes(), rep.payload());
    if (rep.type() == Type::Payload) {
        ListOp<Reference> op;
        op.set(ListOpKind::Explicit, {readArc(reader, true, where)});
        return op;
    }
    if (rep.type() != Type::ReferenceListOp && rep.type() != Type::PayloadListOp)
        throw Failure{rep.payload(), "expected a reference or payload list op, found type " +
                                         std::to_string(static_cast<int>(rep.type()))};
    const bool isPayload = rep.type() == Type::PayloadListOp;
    return readListOp<Reference>(reader, [&] {
        const uint64_t at = reader.tell();
        const uint64_t count = reader.read<uint64_t>();
        if (count > reader.size() / 8) throw Failure{at, "list of " + std::to_string(count) + " arcs cannot fit in the file"};
        std::vector<Reference> arcs;
        for (uint64_t i = 0; i < count; ++i) arcs.push_back(readArc(reader, isPayload, where));
        return arcs;
    });
}

std::vector<LayerOffset> ValueReader::layerOffsets(ValueRep rep) {
    if (rep.type() != Type::LayerOffsetVector)
        throw Failure{rep.payload(), "expected layer offsets, found type " + std::to_string(static_cast<int>(rep.type()))};
    ByteReader reader(file_.bytes(), rep.payload());
    const uint64_t at = reader.tell();
    const uint64_t count = reader.read<uint64_t>();
    if (count > reader.size() / 16) throw Failure{at, "list of " + std::to_string(count) + " layer offsets cannot fit in the file"};
    std::vector<LayerOffset> offsets(count);
    for (LayerOffset& o : offsets) {
        o.offset = reader.read<double>();
        o.scale = reader.read<double>();
    }
    return offsets;
}

void ValueReader::readDictionary(ByteReader& reader, const std::string& prefix, std::map<std::string, Value>& out,
                                 int depth) {
    if (depth > kMaxNesting) throw Failure{reader.tell(), "dictionaries nested deeper than " + std::to_string(kMaxNesting)};
    const uint64_t at = reader.tell();
    const uint64_t count = reader.read<uint64_t>();
    if (count > reader.size() / 12) throw Failure{at, "dictionary of " + std::to_string(count) + " entries cannot fit in the file"};
    spend(count, at);
    for (uint64_t i = 0; i < count; ++i) {
        const std::string key = prefix + file_.string(reader.read<uint32_t>(), reader.tell() - 4);
        // Each value: a forward offset (from where it is written) to its ValueRep.
        const uint64_t start = reader.tell();
        const auto offset = reader.read<int64_t>();
        reader.seek(start + static_cast<uint64_t>(offset));
        const auto rep = ValueRep{reader.read<uint64_t>()};
        if (rep.type() == Type::Dictionary) {
            if (rep.isInlined()) continue;  // empty
            ByteReader nested(file_.bytes(), rep.payload());
            readDictionary(nested, key + ":", out, depth + 1);
        } else if (auto value = this->value(rep, depth + 1)) {
            out[key] = std::move(*value);
        }
    }
}

void ValueReader::dictionary(ValueRep rep, const std::string& prefix, std::map<std::string, Value>& out) {
    if (rep.type() != Type::Dictionary || rep.isInlined()) return;
    ByteReader reader(file_.bytes(), rep.payload());
    readDictionary(reader, prefix, out, 0);
}

std::map<std::string, std::string> ValueReader::variantSelections(ValueRep rep) {
    ByteReader reader(file_.bytes(), rep.payload());
    const uint64_t at = reader.tell();
    const uint64_t count = reader.read<uint64_t>();
    if (count > reader.size() / 8) throw Failure{at, "variant selections of " + std::to_string(count) + " entries"};
    std::map<std::string, std::string> out;
    for (uint64_t i = 0; i < count; ++i) {
        const uint64_t entryAt = reader.tell();
        std::string set = file_.string(reader.read<uint32_t>(), entryAt);
        out[std::move(set)] = file_.string(reader.read<uint32_t>(), entryAt);
    }
    return out;
}

std::map<double, Value> ValueReader::timeSamples(ValueRep rep) {
    // A forward offset to the times' ValueRep, then a forward offset to the values: a count and
    // that many ValueReps.
    ByteReader reader(file_.bytes(), rep.payload());
    const uint64_t timesAt = reader.tell();
    reader.seek(timesAt + static_cast<uint64_t>(reader.read<int64_t>()));
    const auto timesRep = ValueRep{reader.read<uint64_t>()};
    const uint64_t valuesAt = reader.tell();
    reader.seek(valuesAt + static_cast<uint64_t>(reader.read<int64_t>()));
    const uint64_t count = reader.read<uint64_t>();
    const std::optional<Value> times = value(timesRep);
    if (!times || times->numbers.size() != count)
        throw Failure{timesAt, "time samples hold " + std::to_string(count) + " values for " +
                                   std::to_string(times ? times->numbers.size() : 0) + " times"};
    if (count > reader.size() / 8) throw Failure{valuesAt, "time samples cannot fit in the file"};
    spend(count, valuesAt);
    std::map<double, Value> samples;
    for (uint64_t i = 0; i < count; ++i) {
        const uint64_t sampleAt = reader.tell();
        auto sample = value(ValueRep{reader.read<uint64_t>()});
        if (!sample) throw Failure{sampleAt, "time sample of a type that is no value"};
        samples[times->numbers[i]] = std::move(*sample);
    }
    return samples;
}

}  // namespace obscura::usda::crate
