// Meshes: polygons as they are (the renderer triangulates), per-vertex primvars, material binding.
#include <cmath>
#include <string>

#include "harness/import/convert.h"

namespace obscura::harness::importer {

namespace {

// The polygons of a mesh, points and lines left out, with its vertices renumbered in order of
// first use so that vertices only those primitives used are not written.
struct Polygons {
    std::vector<int> counts;
    std::vector<int> indices;
    std::vector<unsigned> vertices;  // the Assimp vertex of each written point
    unsigned dropped = 0;            // point and line primitives
};

Polygons polygonsOf(const aiMesh& mesh) {
    Polygons polygons;
    std::vector<int> written(mesh.mNumVertices, -1);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices < 3) {
            ++polygons.dropped;
            continue;
        }
        polygons.counts.push_back(static_cast<int>(face.mNumIndices));
        for (unsigned k = 0; k < face.mNumIndices; ++k) {
            int& index = written[face.mIndices[k]];
            if (index < 0) {
                index = static_cast<int>(polygons.vertices.size());
                polygons.vertices.push_back(face.mIndices[k]);
            }
            polygons.indices.push_back(index);
        }
    }
    return polygons;
}

// Whether `data` is finite at every written vertex.
template <class T>
bool finiteAt(const T* data, const Polygons& polygons) {
    for (const unsigned v : polygons.vertices)
        if (!isFinite(data[v])) return false;
    return true;
}

std::string integers(const std::vector<int>& values) {
    return array(values.size(), [&](size_t i) { return std::to_string(values[i]); });
}

// A per-vertex array of the written vertices, each element formatted by `element`.
template <class T, class Format>
std::string perVertex(const T* data, const Polygons& polygons, Format element) {
    return array(polygons.vertices.size(), [&](size_t i) { return element(data[polygons.vertices[i]]); });
}

void warnAboutUnsupported(const aiMesh& mesh, const std::string& label, Warnings& warnings) {
    if (mesh.mNumAnimMeshes > 0) warnings.add(label + ": morph targets are not supported; ignored");
    if (mesh.GetNumUVChannels() > 1) warnings.add(label + ": only the first texture coordinate set is imported");
    if (mesh.GetNumColorChannels() > 1) warnings.add(label + ": only the first vertex colour set is imported");
}

std::string vector3(const aiVector3D& v) { return tuple({v.x, v.y, v.z}); }
std::string vector2(const aiVector3D& v) { return tuple({v.x, v.y}); }
std::string rgb(const aiColor4D& c) { return tuple({c.r, c.g, c.b}); }

// Normals, texture coordinates and colours, each left out (with a warning) when not finite.
void writePrimvars(const aiMesh& mesh, const Polygons& polygons, const std::string& label, UsdaWriter& out,
                   Warnings& warnings) {
    if (mesh.HasNormals()) {
        if (finiteAt(mesh.mNormals, polygons)) {
            out.vertexProperty("normal3f[] normals", perVertex(mesh.mNormals, polygons, vector3));
        } else {
            warnings.add(label + ": non-finite normals dropped; the renderer computes them");
        }
    }
    // Assimp's texture coordinates already have USD's origin (bottom left): its glTF importer
    // flips v, and no aiProcess_FlipUVs is asked for. Only u and v of 3D coordinates are used.
    if (mesh.HasTextureCoords(0)) {
        if (finiteAt(mesh.mTextureCoords[0], polygons)) {
            out.vertexProperty("texCoord2f[] primvars:st", perVertex(mesh.mTextureCoords[0], polygons, vector2));
        } else {
            warnings.add(label + ": non-finite texture coordinates dropped");
        }
    }
    if (mesh.HasVertexColors(0)) {
        if (finiteAt(mesh.mColors[0], polygons)) {
            out.vertexProperty("color3f[] primvars:displayColor", perVertex(mesh.mColors[0], polygons, rgb));
        } else {
            warnings.add(label + ": non-finite vertex colours dropped");
        }
    }
}

}  // namespace

void writeMesh(const aiMesh& mesh, const std::vector<MaterialBinding>& materials,
               const std::map<const aiMesh*, std::string>& skeletons, NameScope& siblings, UsdaWriter& out,
               Warnings& warnings) {
    const std::string label = "mesh '" + std::string(mesh.mName.C_Str()) + "'";
    const Polygons polygons = polygonsOf(mesh);
    if (polygons.dropped > 0)
        warnings.add(label + ": " + std::to_string(polygons.dropped) +
                     " point and line primitives dropped (only polygons are imported)");
    if (polygons.counts.empty()) return;
    if (!finiteAt(mesh.mVertices, polygons)) {
        warnings.add(label + ": non-finite points; mesh skipped");
        return;
    }
    warnAboutUnsupported(mesh, label, warnings);

    // Validation guarantees the material index is in range.
    const MaterialBinding& material = materials.at(mesh.mMaterialIndex);
    out.beginPrim("Mesh", siblings.claim(mesh.mName.C_Str(), "Mesh"),
                  {"prepend apiSchemas = [\"MaterialBindingAPI\"]"});
    out.property("int[] faceVertexCounts", integers(polygons.counts));
    out.property("int[] faceVertexIndices", integers(polygons.indices));
    out.property("point3f[] points", perVertex(mesh.mVertices, polygons, vector3));
    writePrimvars(mesh, polygons, label, out, warnings);
    if (const auto skeleton = skeletons.find(&mesh); skeleton != skeletons.end())
        writeSkinBinding(mesh, polygons.vertices, skeleton->second, out);
    // Imported meshes are final polygons, not subdivision cages.
    out.property("uniform token subdivisionScheme", stringLiteral("none"));
    if (material.doubleSided) out.property("uniform bool doubleSided", "1");
    out.property("rel material:binding", pathRef(material.path));
    out.endPrim();
}

}  // namespace obscura::harness::importer
