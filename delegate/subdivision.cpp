#include "delegate/subdivision.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <string_view>
#include <utility>

namespace obscura::delegate {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// A 3-component primvar element in the form OpenSubdiv's PrimvarRefiner templates interpolate:
// Clear() and AddWithWeight() (OpenSubdiv docs, "Far::PrimvarRefiner", far_tutorial_0).
struct Float3 {
    std::array<float, 3> v{};

    void Clear() { v = {}; }
    void AddWithWeight(const Float3& src, float weight) {
        for (size_t j = 0; j < 3; ++j) v[j] += weight * src.v[j];
    }
};

// Primvars of fewer components (st) travel in the first ones, the rest zero.
std::vector<Float3> toFloat3(const std::vector<float>& values, size_t components = 3) {
    std::vector<Float3> out(values.size() / components);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < components; ++j) out[i].v[j] = values[components * i + j];
    return out;
}

std::vector<float> toFloats(const std::vector<Float3>& values, size_t components = 3) {
    std::vector<float> out;
    out.reserve(values.size() * components);
    for (const Float3& value : values) out.insert(out.end(), value.v.begin(), value.v.begin() + long(components));
    return out;
}

// --- USD tokens to OpenSubdiv options --------------------------------------------------------

template <typename Enum, size_t N>
std::optional<Enum> lookupToken(const std::array<std::pair<std::string_view, Enum>, N>& table, const std::string& token) {
    for (const auto& [name, value] : table)
        if (name == token) return value;
    return std::nullopt;
}

template <typename Enum, size_t N>
std::string unknownToken(const char* attribute, const std::string& token,
                         const std::array<std::pair<std::string_view, Enum>, N>& table) {
    std::string known;
    for (const auto& entry : table) known += (known.empty() ? "" : ", ") + std::string(entry.first);
    return std::string(attribute) + ": \"" + token + "\" is not one of " + known;
}

// UsdGeomMesh interpolateBoundary; OpenSubdiv docs, "Subdivision Surfaces: Boundary Interpolation Rules".
constexpr std::array<std::pair<std::string_view, Sdc::Options::VtxBoundaryInterpolation>, 3> kBoundaryTokens{{
    {"none", Sdc::Options::VTX_BOUNDARY_NONE},
    {"edgeOnly", Sdc::Options::VTX_BOUNDARY_EDGE_ONLY},
    {"edgeAndCorner", Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER},
}};

// UsdGeomMesh faceVaryingLinearInterpolation; OpenSubdiv docs, "Face-varying Interpolation Rules".
constexpr std::array<std::pair<std::string_view, Sdc::Options::FVarLinearInterpolation>, 6> kFaceVaryingTokens{{
    {"none", Sdc::Options::FVAR_LINEAR_NONE},
    {"cornersOnly", Sdc::Options::FVAR_LINEAR_CORNERS_ONLY},
    {"cornersPlus1", Sdc::Options::FVAR_LINEAR_CORNERS_PLUS1},
    {"cornersPlus2", Sdc::Options::FVAR_LINEAR_CORNERS_PLUS2},
    {"boundaries", Sdc::Options::FVAR_LINEAR_BOUNDARIES},
    {"all", Sdc::Options::FVAR_LINEAR_ALL},
}};

Sdc::SchemeType sdcScheme(SubdivisionScheme scheme) {
    switch (scheme) {
        case SubdivisionScheme::Loop: return Sdc::SCHEME_LOOP;
        case SubdivisionScheme::Bilinear: return Sdc::SCHEME_BILINEAR;
        default: return Sdc::SCHEME_CATMARK;
    }
}

// --- Validation ------------------------------------------------------------------------------
// The checks of USD's PxOsdMeshTopologyValidation, plus index ranges: OpenSubdiv reads indices
// unchecked, so an out-of-range one would crash inside it instead of failing.

std::string validateFaces(const MeshInput& mesh, SubdivisionScheme scheme) {
    const size_t pointCount = mesh.points.size() / 3;
    size_t total = 0;
    for (size_t f = 0; f < mesh.faceVertexCounts.size(); ++f) {
        const int32_t count = mesh.faceVertexCounts[f];
        if (count < 3) return "faceVertexCounts[" + std::to_string(f) + "] is " + std::to_string(count) + " (a face needs 3 or more)";
        // Loop subdivides triangles only (OpenSubdiv docs, "Loop Subdivision").
        if (scheme == SubdivisionScheme::Loop && count != 3)
            return "faceVertexCounts[" + std::to_string(f) + "] is " + std::to_string(count) + ": loop subdivision needs triangles";
        total += size_t(count);
    }
    if (total != mesh.faceVertexIndices.size())
        return "faceVertexCounts sum to " + std::to_string(total) + " but faceVertexIndices has " +
               std::to_string(mesh.faceVertexIndices.size()) + " entries";
    for (size_t i = 0; i < mesh.faceVertexIndices.size(); ++i) {
        const int32_t index = mesh.faceVertexIndices[i];
        if (index < 0 || size_t(index) >= pointCount)
            return "faceVertexIndices[" + std::to_string(i) + "] = " + std::to_string(index) + " is outside the " +
                   std::to_string(pointCount) + " points";
    }
    return {};
}

std::string checkIndices(const char* attribute, const std::vector<int32_t>& indices, size_t limit, const char* what) {
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] < 0 || size_t(indices[i]) >= limit)
            return std::string(attribute) + "[" + std::to_string(i) + "] = " + std::to_string(indices[i]) + " is outside the " +
                   std::to_string(limit) + " " + what;
    return {};
}

std::string checkSharpnesses(const char* attribute, const std::vector<float>& sharpnesses) {
    for (size_t i = 0; i < sharpnesses.size(); ++i)
        if (!(sharpnesses[i] >= 0.0f))
            return std::string(attribute) + "[" + std::to_string(i) + "] = " + std::to_string(sharpnesses[i]) + " is not a sharpness >= 0";
    return {};
}

std::string validateTags(const MeshInput& mesh, const SubdivisionTags& tags) {
    if (!lookupToken(kBoundaryTokens, tags.interpolateBoundary))
        return unknownToken("interpolateBoundary", tags.interpolateBoundary, kBoundaryTokens);
    if (!lookupToken(kFaceVaryingTokens, tags.faceVaryingLinearInterpolation))
        return unknownToken("faceVaryingLinearInterpolation", tags.faceVaryingLinearInterpolation, kFaceVaryingTokens);

    const size_t pointCount = mesh.points.size() / 3;
    size_t creaseVertices = 0;
    for (size_t i = 0; i < tags.creaseLengths.size(); ++i) {
        if (tags.creaseLengths[i] < 2)
            return "creaseLengths[" + std::to_string(i) + "] is " + std::to_string(tags.creaseLengths[i]) + " (a crease needs 2 or more vertices)";
        creaseVertices += size_t(tags.creaseLengths[i]);
    }
    if (creaseVertices != tags.creaseIndices.size())
        return "creaseLengths sum to " + std::to_string(creaseVertices) + " but creaseIndices has " +
               std::to_string(tags.creaseIndices.size()) + " entries";
    const size_t creaseEdges = creaseVertices - tags.creaseLengths.size();
    if (tags.creaseSharpnesses.size() != tags.creaseLengths.size() && tags.creaseSharpnesses.size() != creaseEdges)
        return "creaseSharpnesses has " + std::to_string(tags.creaseSharpnesses.size()) + " entries, neither one per crease (" +
               std::to_string(tags.creaseLengths.size()) + ") nor one per crease edge (" + std::to_string(creaseEdges) + ")";
    if (tags.cornerSharpnesses.size() != tags.cornerIndices.size())
        return "cornerSharpnesses has " + std::to_string(tags.cornerSharpnesses.size()) + " entries but cornerIndices has " +
               std::to_string(tags.cornerIndices.size());
    for (const std::string& error : {checkIndices("creaseIndices", tags.creaseIndices, pointCount, "points"),
                                     checkSharpnesses("creaseSharpnesses", tags.creaseSharpnesses),
                                     checkIndices("cornerIndices", tags.cornerIndices, pointCount, "points"),
                                     checkSharpnesses("cornerSharpnesses", tags.cornerSharpnesses),
                                     checkIndices("holeIndices", tags.holeIndices, mesh.faceVertexCounts.size(), "faces")})
        if (!error.empty()) return error;
    return {};
}

// --- Topology --------------------------------------------------------------------------------

bool isFaceVarying(const std::optional<MeshPrimvar>& primvar) {
    return primvar && primvar->interpolation == OBSCURA_INTERPOLATION_FACE_VARYING;
}

// A primvar is refined only when its element count fits its interpolation on the input mesh.
bool fitsMesh(const MeshInput& mesh, const std::optional<MeshPrimvar>& primvar) {
    return primvar && primvar->values.size() == primvar->components * primvarElementCount(mesh, primvar->interpolation);
}

// Everything the refiner is built from: equal keys give the same refined topology.
struct TopologyKey {
    std::vector<int32_t> faceVertexCounts, faceVertexIndices;
    size_t pointCount = 0;
    bool leftHanded = false;
    SubdivisionScheme scheme = SubdivisionScheme::None;
    SubdivisionTags tags;
    int level = 0;
    // displayColor, displayOpacity or st is face-varying: the refiner carries a face-varying
    // channel. Each has a value per face-vertex (the host expands indexed primvars), so one channel
    // serves all.
    bool faceVaryingChannel = false;

    bool operator==(const TopologyKey&) const = default;
};

TopologyKey makeKey(const MeshInput& mesh, SubdivisionScheme scheme, const SubdivisionTags& tags, int level) {
    return {mesh.faceVertexCounts, mesh.faceVertexIndices, mesh.points.size() / 3, mesh.leftHanded, scheme, tags, level,
            (isFaceVarying(mesh.displayColor) && fitsMesh(mesh, mesh.displayColor)) ||
                (isFaceVarying(mesh.displayOpacity) && fitsMesh(mesh, mesh.displayOpacity)) ||
                (isFaceVarying(mesh.st) && fitsMesh(mesh, mesh.st))};
}

// USD's creases are runs of consecutive vertices: a run of n vertices makes n - 1 crease edges,
// sharpened by one value per run or one per edge (UsdGeomMesh creaseSharpnesses). OpenSubdiv
// wants vertex pairs with one sharpness each; 10 and above is infinitely sharp in both.
struct CreaseEdges {
    std::vector<int32_t> vertexPairs;
    std::vector<float> sharpnesses;
};

CreaseEdges creaseEdges(const SubdivisionTags& tags) {
    CreaseEdges edges;
    const size_t edgeCount = tags.creaseIndices.size() - tags.creaseLengths.size();
    const bool perEdge = tags.creaseSharpnesses.size() == edgeCount;
    size_t start = 0;
    for (size_t run = 0; run < tags.creaseLengths.size(); ++run) {
        const size_t length = size_t(tags.creaseLengths[run]);
        for (size_t k = 0; k + 1 < length; ++k) {
            edges.vertexPairs.insert(edges.vertexPairs.end(), {tags.creaseIndices[start + k], tags.creaseIndices[start + k + 1]});
            edges.sharpnesses.push_back(tags.creaseSharpnesses[perEdge ? edges.sharpnesses.size() : run]);
        }
        start += length;
    }
    return edges;
}

}  // namespace

// The refiner and the refined faces it yields, precomputed so that evaluation is only primvar math.
struct SubdivisionTopology {
    TopologyKey key;
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::vector<int32_t> faceVertexCounts, faceVertexIndices;  // refined faces, holes removed
    std::vector<int32_t> baseFace;                             // input face each refined face comes from
    std::vector<int32_t> cornerValues;                         // face-varying value of each refined face-vertex
};

namespace {

std::unique_ptr<Far::TopologyRefiner> createRefiner(const TopologyKey& key) {
    Sdc::Options options;
    options.SetVtxBoundaryInterpolation(*lookupToken(kBoundaryTokens, key.tags.interpolateBoundary));
    options.SetFVarLinearInterpolation(*lookupToken(kFaceVaryingTokens, key.tags.faceVaryingLinearInterpolation));

    const CreaseEdges creases = creaseEdges(key.tags);
    // Without indices a face-varying primvar has a value per face-vertex: identity value indices.
    std::vector<int32_t> valueIndices(key.faceVaryingChannel ? key.faceVertexIndices.size() : 0);
    std::iota(valueIndices.begin(), valueIndices.end(), 0);
    Far::TopologyDescriptor::FVarChannel channel;
    channel.numValues = int(valueIndices.size());
    channel.valueIndices = valueIndices.data();

    Far::TopologyDescriptor descriptor;
    descriptor.numVertices = int(key.pointCount);
    descriptor.numFaces = int(key.faceVertexCounts.size());
    descriptor.numVertsPerFace = key.faceVertexCounts.data();
    descriptor.vertIndicesPerFace = key.faceVertexIndices.data();
    descriptor.numCreases = int(creases.sharpnesses.size());
    descriptor.creaseVertexIndexPairs = creases.vertexPairs.data();
    descriptor.creaseWeights = creases.sharpnesses.data();
    descriptor.numCorners = int(key.tags.cornerIndices.size());
    descriptor.cornerVertexIndices = key.tags.cornerIndices.data();
    descriptor.cornerWeights = key.tags.cornerSharpnesses.data();
    descriptor.numHoles = int(key.tags.holeIndices.size());
    descriptor.holeIndices = key.tags.holeIndices.data();
    // OpenSubdiv assumes counter-clockwise faces; for a left-handed mesh it reverses every face
    // (and its face-varying values) as it reads them (Far::TopologyDescriptor::isLeftHanded), so
    // the refined faces come out counter-clockwise.
    descriptor.isLeftHanded = key.leftHanded;
    descriptor.numFVarChannels = key.faceVaryingChannel ? 1 : 0;
    descriptor.fvarChannels = &channel;

    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(descriptor, Factory::Options(sdcScheme(key.scheme), options)));
    if (!refiner) return nullptr;
    // PrimvarRefiner::Limit needs the last level's full topology (Far::TopologyRefiner::UniformOptions).
    Far::TopologyRefiner::UniformOptions uniform(key.level);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);
    return refiner;
}

// Input face of every last-level face: face indices carried down as a uniform primvar.
std::vector<int32_t> lastLevelBaseFaces(const Far::TopologyRefiner& refiner) {
    Far::PrimvarRefiner primvars(refiner);
    std::vector<int32_t> faces(size_t(refiner.GetLevel(0).GetNumFaces()));
    std::iota(faces.begin(), faces.end(), 0);
    for (int level = 1; level <= refiner.GetMaxLevel(); ++level) {
        std::vector<int32_t> children(size_t(refiner.GetLevel(level).GetNumFaces()));
        primvars.InterpolateFaceUniform(level, faces, children);
        faces = std::move(children);
    }
    return faces;
}

std::unique_ptr<SubdivisionTopology> buildTopology(TopologyKey key) {
    auto topology = std::make_unique<SubdivisionTopology>();
    topology->refiner = createRefiner(key);
    if (!topology->refiner) return nullptr;
    topology->key = std::move(key);

    const std::vector<int32_t> baseFaces = lastLevelBaseFaces(*topology->refiner);
    const Far::TopologyLevel& last = topology->refiner->GetLevel(topology->refiner->GetMaxLevel());
    topology->faceVertexCounts.reserve(size_t(last.GetNumFaces()));
    topology->baseFace.reserve(size_t(last.GetNumFaces()));
    topology->faceVertexIndices.reserve(size_t(last.GetNumFaceVertices()));
    if (topology->key.faceVaryingChannel) topology->cornerValues.reserve(size_t(last.GetNumFaceVertices()));
    for (int face = 0; face < last.GetNumFaces(); ++face) {
        // Holes keep their children in the refiner, tagged (Far::TopologyLevel::IsFaceHole);
        // interpolateBoundary none also tags the faces along the boundary as holes.
        if (last.IsFaceHole(face)) continue;
        const Far::ConstIndexArray vertices = last.GetFaceVertices(face);
        topology->faceVertexCounts.push_back(vertices.size());
        topology->faceVertexIndices.insert(topology->faceVertexIndices.end(), vertices.begin(), vertices.end());
        topology->baseFace.push_back(baseFaces[size_t(face)]);
        if (topology->key.faceVaryingChannel) {
            const Far::ConstIndexArray values = last.GetFaceFVarValues(face);
            topology->cornerValues.insert(topology->cornerValues.end(), values.begin(), values.end());
        }
    }
    return topology;
}

// --- Evaluation ------------------------------------------------------------------------------

std::vector<Float3> refineVertexData(const Far::TopologyRefiner& refiner, std::vector<Float3> data, ObscuraInterpolation interpolation) {
    Far::PrimvarRefiner primvars(refiner);
    for (int level = 1; level <= refiner.GetMaxLevel(); ++level) {
        std::vector<Float3> refined(size_t(refiner.GetLevel(level).GetNumVertices()));
        if (interpolation == OBSCURA_INTERPOLATION_VARYING)
            primvars.InterpolateVarying(level, data, refined);
        else
            primvars.Interpolate(level, data, refined);
        data = std::move(refined);
    }
    return data;
}

std::vector<Float3> refineFaceVaryingData(const Far::TopologyRefiner& refiner, std::vector<Float3> data) {
    Far::PrimvarRefiner primvars(refiner);
    for (int level = 1; level <= refiner.GetMaxLevel(); ++level) {
        std::vector<Float3> refined(size_t(refiner.GetLevel(level).GetNumFVarValues()));
        primvars.InterpolateFaceVarying(level, data, refined);
        data = std::move(refined);
    }
    return data;
}

// Normals of the limit surface at the last level's vertices: the cross product of the two limit
// tangents (Far::PrimvarRefiner::Limit), which points out of counter-clockwise faces.
std::vector<float> limitNormals(const Far::TopologyRefiner& refiner, const std::vector<Float3>& refinedPoints) {
    std::vector<Float3> limit(refinedPoints.size()), tangent1(refinedPoints.size()), tangent2(refinedPoints.size());
    Far::PrimvarRefiner(refiner).Limit(refinedPoints, limit, tangent1, tangent2);
    std::vector<float> normals;
    normals.reserve(3 * refinedPoints.size());
    for (size_t i = 0; i < refinedPoints.size(); ++i) {
        const auto& a = tangent1[i].v;
        const auto& b = tangent2[i].v;
        const std::array<float, 3> n{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        // A vertex without tangents (one only hole faces use) keeps a zero normal.
        for (float component : n) normals.push_back(length > 0.0f ? component / length : 0.0f);
    }
    return normals;
}

MeshPrimvar refinePrimvar(const SubdivisionTopology& topology, const MeshPrimvar& primvar) {
    const size_t n = primvar.components;
    MeshPrimvar out{{}, primvar.interpolation, n};
    switch (primvar.interpolation) {
        case OBSCURA_INTERPOLATION_CONSTANT: out.values = primvar.values; break;
        case OBSCURA_INTERPOLATION_UNIFORM:
            out.values.reserve(n * topology.baseFace.size());
            for (int32_t face : topology.baseFace) {
                const auto first = primvar.values.begin() + long(n * size_t(face));
                out.values.insert(out.values.end(), first, first + long(n));
            }
            break;
        case OBSCURA_INTERPOLATION_FACE_VARYING: {
            const std::vector<Float3> values = refineFaceVaryingData(*topology.refiner, toFloat3(primvar.values, n));
            out.values.reserve(n * topology.cornerValues.size());
            for (int32_t value : topology.cornerValues) {
                const auto& v = values[size_t(value)].v;
                out.values.insert(out.values.end(), v.begin(), v.begin() + long(n));
            }
            break;
        }
        default:
            out.values = toFloats(refineVertexData(*topology.refiner, toFloat3(primvar.values, n), primvar.interpolation), n);
            break;
    }
    return out;
}

MeshInput evaluate(const SubdivisionTopology& topology, const MeshInput& mesh) {
    MeshInput out;
    const std::vector<Float3> points = refineVertexData(*topology.refiner, toFloat3(mesh.points), OBSCURA_INTERPOLATION_VERTEX);
    out.points = toFloats(points);
    out.faceVertexCounts = topology.faceVertexCounts;
    out.faceVertexIndices = topology.faceVertexIndices;
    out.leftHanded = false;
    out.normals = MeshPrimvar{limitNormals(*topology.refiner, points), OBSCURA_INTERPOLATION_VERTEX};
    if (fitsMesh(mesh, mesh.displayColor)) out.displayColor = refinePrimvar(topology, *mesh.displayColor);
    if (fitsMesh(mesh, mesh.displayOpacity)) out.displayOpacity = refinePrimvar(topology, *mesh.displayOpacity);
    if (fitsMesh(mesh, mesh.st)) out.st = refinePrimvar(topology, *mesh.st);
    // Refined faces draw with their input face's material: the surface stays one, split only
    // where the drawn triangles are grouped.
    if (mesh.faceGroups.size() == mesh.faceVertexCounts.size())
        for (int32_t face : topology.baseFace) out.faceGroups.push_back(mesh.faceGroups[size_t(face)]);
    return out;
}

}  // namespace

SubdivisionScheme parseSubdivisionScheme(const std::string& token) {
    if (token == "none") return SubdivisionScheme::None;
    if (token == "loop") return SubdivisionScheme::Loop;
    if (token == "bilinear") return SubdivisionScheme::Bilinear;
    return SubdivisionScheme::CatmullClark;
}

SubdivisionCache::SubdivisionCache() = default;
SubdivisionCache::~SubdivisionCache() = default;
SubdivisionCache::SubdivisionCache(SubdivisionCache&&) noexcept = default;
SubdivisionCache& SubdivisionCache::operator=(SubdivisionCache&&) noexcept = default;

void SubdivisionCache::release() { topology_.reset(); }

std::variant<MeshInput, std::string> SubdivisionCache::refine(const MeshInput& mesh, SubdivisionScheme scheme,
                                                              const SubdivisionTags& tags, int level) {
    if (level > kMaxRefineLevel)
        return "refine level " + std::to_string(level) + " is above the maximum of " + std::to_string(kMaxRefineLevel);
    if (level <= 0 || scheme == SubdivisionScheme::None) return mesh;
    for (const std::string& error : {validateFaces(mesh, scheme), validateTags(mesh, tags)})
        if (!error.empty()) return error;
    // An empty mesh has nothing to refine, and OpenSubdiv refuses a mesh without vertices.
    if (mesh.faceVertexCounts.empty()) return mesh;

    TopologyKey key = makeKey(mesh, scheme, tags, level);
    if (!topology_ || topology_->key != key) {
        topology_ = buildTopology(std::move(key));
        if (!topology_) return std::string("OpenSubdiv rejected the mesh topology");
        ++topologyBuilds_;
    }
    return evaluate(*topology_, mesh);
}

std::variant<MeshInput, std::string> refineMesh(const MeshInput& mesh, SubdivisionScheme scheme, const SubdivisionTags& tags,
                                                int level) {
    return SubdivisionCache().refine(mesh, scheme, tags, level);
}

}  // namespace obscura::delegate
