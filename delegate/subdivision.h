// Subdivision surfaces with OpenSubdiv: refines a USD mesh (Catmull-Clark, Loop or bilinear)
// uniformly to a level and returns the refined control mesh with limit-surface normals, ready for
// buildMeshGeometry. Pure CPU code: no Vulkan, unit-tested on its own.
#pragma once

#include "delegate/mesh_builder.h"

#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace obscura::delegate {

enum class SubdivisionScheme { None, CatmullClark, Loop, Bilinear };

// UsdGeomMesh subdivisionScheme tokens: catmullClark, loop, bilinear, none. Any other token gives
// USD's fallback, catmullClark (the schema's checkValue rejects such tokens before they get here).
SubdivisionScheme parseSubdivisionScheme(const std::string& token);

// The UsdGeomMesh attributes that shape the limit surface, with USD's fallback values.
struct SubdivisionTags {
    std::string interpolateBoundary = "edgeAndCorner";            // none | edgeOnly | edgeAndCorner
    std::string faceVaryingLinearInterpolation = "cornersPlus1";  // all | none | boundaries | cornersOnly | cornersPlus1 | cornersPlus2
    std::vector<int32_t> creaseIndices, creaseLengths;            // runs of consecutive vertices
    std::vector<float> creaseSharpnesses;                         // one per run or one per edge
    std::vector<int32_t> cornerIndices;
    std::vector<float> cornerSharpnesses;
    std::vector<int32_t> holeIndices;                             // faces left out of the surface

    bool operator==(const SubdivisionTags&) const = default;
};

// The refinement levels accepted; above kMaxRefineLevel each level quadruples the faces.
inline constexpr int kMaxRefineLevel = 6;

// Refines `mesh` uniformly `level` times. level <= 0 or scheme None returns the mesh unchanged;
// level > kMaxRefineLevel is an error. The result:
// - points: every refined vertex (vertices only used by hole faces included, so vertex primvars
//   keep one element per point);
// - faces: the refined quads (Catmull-Clark, bilinear) or triangles (Loop), holes removed,
//   wound counter-clockwise: leftHanded is false even for a left-handed input;
// - normals: limit-surface normals, vertex interpolated. Authored normals are ignored, as
//   UsdGeomMesh specifies for subdivision surfaces;
// - displayColor and st: refined by their interpolation (constant kept, uniform copied from the
//   parent face, vertex/varying/faceVarying interpolated). One whose element count does not fit
//   its interpolation on the input mesh is dropped: check it with primvarElementCount to warn.
//   Face-varying values are not shared between faces (hosts expand indexed primvars), so each
//   face refines its own values with the face-varying boundary rules;
// - faceGroups: each refined face's is that of the input face it comes from.
// Returns the reason for topology or tags that USD's validation (PxOsdMeshTopologyValidation)
// or OpenSubdiv rejects. Non-manifold edges are not an error: OpenSubdiv refines them as sharp.
std::variant<MeshInput, std::string> refineMesh(const MeshInput& mesh, SubdivisionScheme scheme,
                                                const SubdivisionTags& tags, int level);

// OpenSubdiv's refiner for one topology and what it was built from (defined in subdivision.cpp,
// which keeps OpenSubdiv's headers out of this one).
struct SubdivisionTopology;

// refineMesh for a mesh refined again and again: keeps OpenSubdiv's topology refiner between
// calls and rebuilds it only when what it was built from changed (the face counts and indices,
// point count, orientation, scheme, tags, level, or whether displayColor or st is face-varying), so
// animated points re-evaluate without rebuilding topology.
class SubdivisionCache {
public:
    SubdivisionCache();
    ~SubdivisionCache();
    SubdivisionCache(SubdivisionCache&&) noexcept;
    SubdivisionCache& operator=(SubdivisionCache&&) noexcept;

    std::variant<MeshInput, std::string> refine(const MeshInput& mesh, SubdivisionScheme scheme,
                                                const SubdivisionTags& tags, int level);

    // Drops the kept refiner, for a mesh that will not refine again: it holds every level's
    // topology relations (the Open Chess Set's refiners were two thirds of the process's peak).
    void release();

    // How many times a refiner was built (failed builds not counted): for tests.
    uint64_t topologyBuilds() const { return topologyBuilds_; }

private:
    std::unique_ptr<SubdivisionTopology> topology_;
    uint64_t topologyBuilds_ = 0;
};

}  // namespace obscura::delegate
