// The structure of a USD crate file (.usdc), as OpenUSD writes it (pxr/usd/sdf/crateFile.cpp):
// an 88-byte bootstrap ("PXR-USDC", version, offset of the table of contents), the table of
// contents (named sections), and the structural sections TOKENS, STRINGS, FIELDS, FIELDSETS,
// PATHS and SPECS. Values stay in the file and are decoded on demand (crate_values.h).
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "harness/usda/crate_compression.h"

namespace obscura::usda::crate {

// Bounds-checked little-endian reads from the file's bytes.
class ByteReader {
public:
    explicit ByteReader(std::span<const char> bytes, uint64_t position = 0) : bytes_(bytes), position_(position) {}
    uint64_t tell() const { return position_; }
    void seek(uint64_t position) { position_ = position; }
    uint64_t size() const { return bytes_.size(); }
    template <class T>
    T read() {
        T value;
        std::memcpy(&value, take(sizeof(T)).data(), sizeof(T));
        return value;
    }
    // The next `count` bytes, or a Failure when the file ends first.
    std::span<const char> take(uint64_t count);

private:
    std::span<const char> bytes_;
    uint64_t position_;
};

struct Version {
    int major = 0, minor = 0, patch = 0;
    bool atLeast(int wantMajor, int wantMinor) const {
        return major != wantMajor ? major > wantMajor : minor >= wantMinor;
    }
    std::string str() const;
};

// The oldest and newest versions read: 0.4.0 compressed the structural sections (older files
// are rare and laid out differently); 0.11.0 added relocates and 0.12.0 splines, the last type
// read here.
constexpr Version kOldestVersion{0, 4, 0};
constexpr Version kNewestVersion{0, 12, 0};

// Value types of a ValueRep (pxr/usd/sdf/crateDataTypes.h).
enum class Type : uint8_t {
    Invalid = 0, Bool = 1, UChar = 2, Int = 3, UInt = 4, Int64 = 5, UInt64 = 6, Half = 7, Float = 8,
    Double = 9, String = 10, Token = 11, AssetPath = 12, Matrix2d = 13, Matrix3d = 14, Matrix4d = 15,
    Quatd = 16, Quatf = 17, Quath = 18, Vec2d = 19, Vec2f = 20, Vec2h = 21, Vec2i = 22, Vec3d = 23,
    Vec3f = 24, Vec3h = 25, Vec3i = 26, Vec4d = 27, Vec4f = 28, Vec4h = 29, Vec4i = 30, Dictionary = 31,
    TokenListOp = 32, StringListOp = 33, PathListOp = 34, ReferenceListOp = 35, IntListOp = 36,
    Int64ListOp = 37, UIntListOp = 38, UInt64ListOp = 39, PathVector = 40, TokenVector = 41,
    Specifier = 42, Permission = 43, Variability = 44, VariantSelectionMap = 45, TimeSamples = 46,
    Payload = 47, DoubleVector = 48, LayerOffsetVector = 49, StringVector = 50, ValueBlock = 51,
    Value = 52, UnregisteredValue = 53, UnregisteredValueListOp = 54, PayloadListOp = 55,
    TimeCode = 56, PathExpression = 57, Relocates = 58, Spline = 59, AnimationBlock = 60,
};

// A field's value: a type, three flags and a 48-bit payload (the value itself when inlined,
// otherwise the file offset where it is stored).
struct ValueRep {
    uint64_t bits = 0;
    Type type() const { return static_cast<Type>((bits >> 48) & 0xFF); }
    bool isArray() const { return bits & (uint64_t(1) << 63); }
    bool isInlined() const { return bits & (uint64_t(1) << 62); }
    bool isCompressed() const { return bits & (uint64_t(1) << 61); }
    uint64_t payload() const { return bits & ((uint64_t(1) << 48) - 1); }
};

// SdfSpecType.
enum class SpecType : uint32_t {
    Unknown = 0, Attribute = 1, Connection = 2, Expression = 3, Mapper = 4, MapperArg = 5, Prim = 6,
    PseudoRoot = 7, Relationship = 8, RelationshipTarget = 9, Variant = 10, VariantSet = 11,
};

struct Field {
    uint32_t token = 0;
    ValueRep rep;
};

struct Spec {
    uint32_t path = 0;
    uint32_t fieldSet = 0;  // index of the first field index of a run ended by ~0u
    SpecType type = SpecType::Unknown;
};

// One scene path, as its parent plus one element.
struct PathNode {
    enum class Kind { Root, Prim, Property, Variant };
    Kind kind = Kind::Root;
    int64_t parent = -1;
    std::string name;        // prim or property name; the variant set of a Variant
    std::string variant;     // the selection of a Variant ("" for the variant set's own spec)
    std::string text;        // "/A/B", "/A.prop", "/A{set=sel}", "/A{set=sel}/B" (harness convention)
    int depth = 0;           // elements below the root
};

// Paths nested deeper than this are refused, as the text reader refuses deeper nesting: the
// composer recurses once per level.
constexpr int kMaxPathDepth = 200;

class File {
public:
    // Reads the bootstrap, table of contents and structural sections; throws Failure.
    explicit File(std::span<const char> bytes);

    std::span<const char> bytes() const { return bytes_; }
    const Version& version() const { return version_; }
    const std::string& token(uint64_t index, uint64_t at) const;
    const std::string& string(uint64_t index, uint64_t at) const;  // STRINGS holds token indexes
    const PathNode& path(uint64_t index, uint64_t at) const;
    // The text of a path, "" for the empty path (a reference to a layer's default prim).
    const std::string& pathText(uint64_t index, uint64_t at) const;
    const std::vector<Field>& fields() const { return fields_; }
    const std::vector<uint32_t>& fieldSets() const { return fieldSets_; }
    const std::vector<Spec>& specs() const { return specs_; }
    const std::vector<PathNode>& paths() const { return paths_; }

private:
    struct Section {
        uint64_t start = 0, size = 0;
    };
    Section section(const char* name) const;
    void readTokens(Section section);
    void readStrings(Section section);
    void readFields(Section section);
    void readFieldSets(Section section);
    void readPaths(Section section);
    void readSpecs(Section section);
    // A count read from the file, refused when `count` elements of `bytesEach` cannot fit in it.
    uint64_t checkedCount(uint64_t count, uint64_t bytesEach, uint64_t at) const;
    // uint64 compressed size, then coded integers.
    template <class Int>
    std::vector<Int> readCompressedIntegers(ByteReader& reader, uint64_t count) const;

    std::span<const char> bytes_;
    Version version_;
    std::vector<std::pair<std::string, Section>> sections_;
    std::vector<std::string> tokens_;
    std::vector<uint32_t> strings_;
    std::vector<Field> fields_;
    std::vector<uint32_t> fieldSets_;
    std::vector<PathNode> paths_;
    std::vector<Spec> specs_;
};

}  // namespace obscura::usda::crate
