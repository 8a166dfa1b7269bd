// A composed USD stage read from USD's text format (.usda): the harness's scene model.
// Parsing (usda_parser.*) builds layers; composition (composer.*, prim_index.*) merges sublayers, references
// and payloads into one prim tree; values are evaluated at a time code as USD does.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <variant>
#include <vector>

#include "harness/usda/shared_array.h"
#include "harness/usda/spline.h"

namespace obscura::usda {

// Where something is in a text file; line and column are 1-based.
struct SourceLocation {
    std::string file;
    int line = 0;
    int column = 0;
};

// A readable error: "file:line:column: message".
struct Error {
    SourceLocation where;
    std::string message;
    std::string str() const;
};

// A value of any USD type, flattened for consumers:
//  - numbers (bool, ints, floats, doubles, halfs, vectors, colours, quaternions, matrices, and
//    arrays of those) go to `numbers`, components in file order (quaternions as USD writes them:
//    real part first), `tupleSize` components per element;
//  - strings, tokens, asset paths and paths go to `strings`.
// Both are shared between copies (shared_array.h): a Value copied into a composed prim, or
// returned by Attribute::evaluate, shares its layer's elements until it is edited.
struct Value {
    std::string typeName;              // USD type name without "[]": "float3", "token", "matrix4d"...
    bool isArray = false;
    int tupleSize = 1;                 // 3 for float3, 4 for quatf, 16 for matrix4d
    SharedArray<double> numbers;
    SharedArray<std::string> strings;
    bool blocked = false;              // authored as None: no value (only seen in timeSamples)
    size_t size() const;               // element count
    bool empty() const { return numbers.empty() && strings.empty(); }
};

struct Attribute {
    std::string name;                  // "points", "xformOp:translate", "inputs:diffuseColor"
    std::string typeName;              // as written: "point3f[]", "uniform token"
    bool isUniform = false;
    bool isCustom = false;
    std::optional<Value> defaultValue;
    std::map<double, Value> timeSamples;
    std::shared_ptr<const Spline> spline;  // in stage time; set only where no time samples are
    std::optional<std::string> connection;        // target path of `.connect`, e.g. "/M/S.outputs:rgb"
    std::map<std::string, Value> metadata;        // interpolation, elementSize, ...
    SourceLocation where;

    bool isAnimated() const { return timeSamples.size() > 1 || (spline && spline->varies()); }
    // The value at a time code: time samples or the spline win over the default; linear
    // interpolation for numeric types, slerp for quaternions, held (the earlier sample) for
    // everything else. A spline without a value there (a segment or extrapolation of mode none)
    // gives none.
    std::optional<Value> evaluate(double time) const;
};

struct Relationship {
    std::string name;
    std::vector<std::string> targets;  // absolute prim (or property) paths
    SourceLocation where;              // the strongest spec
    std::map<std::string, Value> metadata;  // bindMaterialAs, ...
};

enum class Specifier { Def, Over, Class };

struct Prim {
    std::string name;
    std::string path;                  // "/World/Mesh"
    std::string typeName;              // "Mesh", "Xform", "" for typeless
    Specifier specifier = Specifier::Def;
    std::string kind;
    bool active = true;
    std::vector<std::string> apiSchemas;
    std::map<std::string, Attribute> attributes;
    std::map<std::string, Relationship> relationships;
    std::map<std::string, Value> metadata;
    // For an instance (instanceable = true, and composition arcs bring its content): USD's
    // instancing key (usda/instancing_key.h); instances with one key share one prototype. "" else.
    std::string instancingKey;
    Prim* parent = nullptr;
    std::vector<std::unique_ptr<Prim>> children;
    SourceLocation where;

    const Attribute* attribute(const std::string& attrName) const;
    const Relationship* relationship(const std::string& relName) const;
};

struct StageMetadata {
    std::string upAxis = "Y";
    double metersPerUnit = 0.01;
    double timeCodesPerSecond = 24.0;
    double framesPerSecond = 24.0;
    std::optional<double> startTimeCode;
    std::optional<double> endTimeCode;
    std::string defaultPrim;
    std::string renderSettingsPrimPath;  // UsdRenderSettings::GetStageRenderSettings; "" when unset
    SourceLocation where;                // the root layer (no line), for messages about its metadata
    std::string doc;
};

// Bounds on what composing one stage may build, so that a small file cannot take the machine
// down: arcs that fan out at every level grow a stage exponentially (a "billion laughs" of scene
// description), and one list naming a large prim many times multiplies its index. Each limit is
// checked as the structure grows, before the next piece is built. The defaults suit a 2-core
// machine with 24 GB: the scene description may hold a twelfth of it, the renderer's copy of the
// geometry and its images need the rest; a stage at the limits composes in well under a minute.
struct CompositionLimits {
    size_t maxPrims = 1'000'000;               // prims on the composed stage
    size_t maxIndexNodes = 10'000;             // nodes (composition arcs) in one prim's index
    size_t maxMemoryBytes = size_t(2) << 30;   // what the stage and its prim indexes hold (estimated)
};

// Variant fallbacks by variant set name, as UsdStage's global variant fallbacks (a plugInfo's
// "UsdVariantFallbacks", Usd.Stage.SetGlobalVariantFallbacks): a set with no authored selection
// takes the first listed variant it has. An authored selection always wins.
using VariantFallbacks = std::map<std::string, std::vector<std::string>>;

// How a stage is loaded.
struct StageOptions {
    CompositionLimits limits;
    VariantFallbacks variantFallbacks;
};

// Diagnostics that are not errors (unknown types, unsupported features): one per kind.
struct Warning {
    SourceLocation where;
    std::string message;
};

class Stage {
public:
    // Parse the root layer and everything it sublayers, references and payloads (asset paths
    // relative to the layer that names them), and compose one prim tree.
    static std::variant<std::unique_ptr<Stage>, Error> open(const std::filesystem::path& file,
                                                            const StageOptions& options = {});
    // Same from text in memory (references resolve relative to `virtualPath`'s folder).
    static std::variant<std::unique_ptr<Stage>, Error> openFromString(const std::string& text,
                                                                       const std::string& virtualPath,
                                                                       const StageOptions& options = {});

    const StageMetadata& metadata() const { return metadata_; }
    const Prim& pseudoRoot() const { return *root_; }
    const Prim* find(const std::string& path) const;
    // Every defined (specifier Def), active prim, depth-first, parents before children;
    // `class` prims and their descendants are excluded.
    std::vector<const Prim*> prims() const;
    const std::vector<Warning>& warnings() const { return warnings_; }

    // Local transform of a prim from its xformOps and xformOpOrder at `time` (USD convention:
    // row-major, row vectors, translation in [12..14]); `resetsXformStack` reports
    // "!resetXformStack!".
    std::array<double, 16> localTransform(const Prim& prim, double time, bool* resetsXformStack = nullptr) const;
    // Product of local transforms up to the root (honouring resetXformStack).
    std::array<double, 16> worldTransform(const Prim& prim, double time) const;
    // The time codes in [from, to] at which any xformOp of the prim or its ancestors is sampled
    // (sorted): its time samples, or where a spline's shape changes and steps along its curves
    // (Spline::sampleTimes; looping extrapolation repeats only within a finite interval).
    std::vector<double> transformSampleTimes(const Prim& prim, double from = -std::numeric_limits<double>::infinity(),
                                             double to = std::numeric_limits<double>::infinity()) const;
    // Computed visibility: "invisible" on the prim or any ancestor at `time`.
    bool isVisible(const Prim& prim, double time) const;
    // Whether the computed visibility can change over time: the prim's or an ancestor's
    // visibility is time-sampled.
    bool hasAnimatedVisibility(const Prim& prim) const;
    // Computed purpose (UsdGeomImageable::ComputePurpose): the purpose authored on the prim, else
    // its nearest imageable ancestor's; null when none is authored (the fallback, "default").
    // Purpose is uniform: its value is the attribute's default.
    const Attribute* purposeOpinion(const Prim& prim) const;
    // UsdGeomPrimvarsAPI::FindInheritablePrimvars: the primvars `prim` hands down to its
    // descendants, by name: its own and its ancestors' of constant interpolation with an authored
    // value, the nearest of each name (one of another interpolation stops those above it).
    std::map<std::string, const Attribute*> inheritablePrimvars(const Prim& prim) const;
    // FindPrimvarWithInheritance: primvar `name` ("primvars:displayColor") of the prim when it
    // authors a value, else the one its ancestors hand down; null when neither.
    const Attribute* primvar(const Prim& prim, const std::string& name) const;
    // The prim, `prim` or an ancestor, whose attribute `attribute` is (an inherited primvar's
    // :indices are its owner's); `prim` when none is.
    const Prim& primAuthoring(const Prim& prim, const Attribute& attribute) const;

private:
    Stage();
    friend class Composer;
    StageMetadata metadata_;
    std::unique_ptr<Prim> root_;
    std::vector<Warning> warnings_;
    std::unordered_map<std::string, const Prim*> primsByPath_;
};

}  // namespace obscura::usda
