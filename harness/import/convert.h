// Internal to the Assimp importer: the pieces of the conversion, each writing its prims.
#pragma once

#include <assimp/scene.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "harness/import/usda_writer.h"

namespace obscura::harness::importer {

enum class SourceFormat { Gltf, Fbx, Obj };

// Messages for the user, each kept once however often it is raised.
class Warnings {
public:
    void add(const std::string& message);
    std::vector<std::string> take() { return std::move(messages_); }

private:
    std::vector<std::string> messages_;
    std::set<std::string> seen_;
};

struct Source {
    const aiScene& scene;
    std::filesystem::path file;  // absolute
    SourceFormat format;
    double metersPerUnit;
};

// The first animation's node channels, the only animation written (a USD layer has one timeline).
struct Timeline {
    double ticksPerSecond = 24.0;
    std::optional<std::pair<double, double>> range;  // first and last key time, in ticks
    std::map<const aiNode*, const aiNodeAnim*> channels;
};

struct MaterialBinding {
    std::string path;  // "/Root/Looks/Name"
    bool doubleSided = false;
};

// Non-finite numbers are never written: they would poison transforms and shading downstream.
inline bool isFinite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool isFinite(const aiQuaternion& q) {
    return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}
inline bool isFinite(const aiColor3D& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }
inline bool isFinite(const aiColor4D& c) { return isFinite(aiColor3D(c.r, c.g, c.b)) && std::isfinite(c.a); }
inline bool isFinite(const aiMatrix4x4& m) {
    for (unsigned row = 0; row < 4; ++row)
        for (unsigned column = 0; column < 4; ++column)
            if (!std::isfinite(m[row][column])) return false;
    return true;
}
// Assimp's matrices act on column vectors, USD's on row vectors: the USD matrix is the transpose.
std::array<float, 16> toUsdMatrix(const aiMatrix4x4& m);
// `xformOp:transform` set to `m` and the xformOpOrder naming it.
void writeMatrixTransform(const aiMatrix4x4& m, UsdaWriter& out);

Timeline readTimeline(const aiScene& scene, Warnings& warnings);

// Into the open Looks scope at `looksPath`: one Material per Assimp material; the bindings are
// indexed like scene.mMaterials.
std::vector<MaterialBinding> writeMaterials(const Source& source, const std::string& looksPath, UsdaWriter& out,
                                            Warnings& warnings);

// `skeletons`: the Skeleton of each skinned mesh (writeSkeletons).
void writeMesh(const aiMesh& mesh, const std::vector<MaterialBinding>& materials,
               const std::map<const aiMesh*, std::string>& skeletons, NameScope& siblings, UsdaWriter& out,
               Warnings& warnings);

// UsdSkel (convert_skins.cpp). Whether any mesh has bones: Root is then a SkelRoot.
bool hasSkinnedMeshes(const aiScene& scene);
// Into the open scope at `scopePath`: a Skeleton (and its SkelAnimation) for each skinned mesh whose
// bones are usable; their paths by mesh.
std::map<const aiMesh*, std::string> writeSkeletons(const Source& source, const Timeline& timeline,
                                                    const std::string& scopePath, UsdaWriter& out, Warnings& warnings);
// Into the open Mesh: its skel:skeleton binding and joint influences, for the written vertices
// (`writtenVertices`: the Assimp vertex of each point).
void writeSkinBinding(const aiMesh& mesh, const std::vector<unsigned>& writtenVertices, const std::string& skeleton,
                      UsdaWriter& out);

void writeCamera(const Source& source, const aiCamera& camera, NameScope& siblings, UsdaWriter& out,
                 Warnings& warnings);
void writeLight(const Source& source, const aiLight& light, NameScope& siblings, UsdaWriter& out,
                Warnings& warnings);

// Into the open Root prim, which stands for Assimp's root node: that node's transform (inside
// `rootCorrection`, the file's axes turned Y-up), its meshes, cameras and lights, and its child nodes
// as Xforms. `names` holds the names already used under Root.
void writeRootContents(const Source& source, const Timeline& timeline, const std::vector<MaterialBinding>& materials,
                       const std::map<const aiMesh*, std::string>& skeletons,
                       const std::optional<aiMatrix4x4>& rootCorrection, NameScope& names, UsdaWriter& out,
                       Warnings& warnings);

}  // namespace obscura::harness::importer
