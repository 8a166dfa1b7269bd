// UsdGeomTetMesh as the triangle mesh of its surface, as the plugin draws meshes: the authored
// surfaceFaceVertexIndices, else the faces UsdGeomTetMesh::ComputeSurfaceFaces computes (each
// tet's four faces, wound to face out of a tet of positive orientation; those that occur once are
// the surface). The tets' points are the mesh's.
#pragma once

#include "harness/usda/bezier_curves.h"

#include <string>
#include <variant>
#include <vector>

namespace obscura::usda {

// The faces of the tets (four point indices each) that no other tet shares, three point indices
// each, sorted as UsdGeomTetMesh sorts them (so that face order does not depend on hashing).
std::vector<int> tetSurfaceFaces(const std::vector<int>& tetVertexIndices);

// The surface triangles (three point indices each) of a TetMesh prim at `time`, or what makes its
// indices unusable (not whole tets or triangles, or a point index outside the points).
std::variant<std::vector<int>, AttributeProblem> tetMeshSurface(const Prim& prim, double time);

// What makes a TetMesh's uniform or faceVarying primvar of `count` values (`elementSize` to an
// element) not fit its surface of `surfaceFaces` triangles ("" when it fits). Hydra draws a TetMesh
// as the mesh of its surface and keeps the prim's primvars as authored (UsdImagingTetMeshAdapter::
// GetTopology, HdsiTetMeshConversionSceneIndex; UsdGeomTetMesh defines no other mapping), so a
// uniform primvar holds one element per surface face and a faceVarying one one per surface face
// corner, in the surface's order, as on a Mesh.
std::string tetSurfacePrimvarProblem(size_t surfaceFaces, size_t count, const std::string& interpolation,
                                     size_t elementSize);

}  // namespace obscura::usda
