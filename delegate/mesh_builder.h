// Turns a USD mesh (points, face counts and indices, primvars with their interpolation) into the
// triangle list the G-buffer pass draws. Pure CPU code: no Vulkan, unit-tested on its own.
#pragma once

#include "passes/frame_data.h"

#include <obscura/obscura.h>

#include <optional>
#include <variant>
#include <string>
#include <vector>

namespace obscura::delegate {

struct MeshPrimvar {
    std::vector<float> values;  // `components` per element
    ObscuraInterpolation interpolation = OBSCURA_INTERPOLATION_VERTEX;
    size_t components = 3;
};

struct MeshInput {
    std::vector<float> points;  // xyz
    std::vector<int32_t> faceVertexCounts;
    std::vector<int32_t> faceVertexIndices;
    bool leftHanded = false;
    std::optional<MeshPrimvar> normals;
    std::optional<MeshPrimvar> displayColor;
    std::optional<MeshPrimvar> displayOpacity;  // 1 component
    std::optional<MeshPrimvar> st;  // texture coordinates, 2 components
    // Per face, the material it draws with, as a number the prim gives meaning to (the mesh's
    // own binding, or one of its material subsets); empty: every face is in group 0.
    std::vector<uint32_t> faceGroups;
};

// A run of a mesh's indices: `count` from `first`.
struct IndexRange {
    uint32_t first = 0;
    uint32_t count = 0;
};

struct MeshGeometry {
    std::vector<passes::Vertex> vertices;
    // The triangles ordered by their face's group (MeshInput::faceGroups), each group's in face
    // order; groupRanges[g] is where group g's are (groups past its end have none).
    std::vector<uint32_t> indices;
    std::vector<IndexRange> groupRanges;
    std::vector<std::string> warnings;  // primvars dropped for a wrong element count, ...
};

// Expected element count of a primvar of this interpolation on this mesh.
size_t primvarElementCount(const MeshInput& mesh, ObscuraInterpolation interpolation);

// Why `primvar` (named `name` in messages) is left out of `mesh`: its element count does not fit
// its interpolation. "" when it fits or is not authored.
std::string primvarCountProblem(const MeshInput& mesh, const std::optional<MeshPrimvar>& primvar, const char* name);

// The count problems of the primvars refinement interpolates (displayColor, displayOpacity, st),
// each naming its primvar: refinement leaves them out, as buildMeshGeometry does.
std::vector<std::string> interpolatedPrimvarProblems(const MeshInput& mesh);

// Validates topology (counts >= 3 and summing to the index count, indices within the points)
// and returns the reason when the mesh is unusable. Primvars of the wrong size are dropped with
// a warning: the mesh still draws. Without authored normals, smooth vertex normals are computed
// (area-weighted face normals), as Hydra does for unrefined meshes. Face-vertices whose vertices
// are equal are one vertex, the first made.
std::variant<MeshGeometry, std::string> buildMeshGeometry(const MeshInput& mesh);

// The drawn positions of built geometry (xyz per vertex): a tessellation's at the shutter's ends.
std::vector<float> positionsOf(const MeshGeometry& geometry);

}  // namespace obscura::delegate
