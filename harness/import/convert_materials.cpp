// Materials: one UsdPreviewSurface per Assimp material, with the base colour texture when the file
// names one.
#include <assimp/material.h>
#include <assimp/scene.h>
#include <assimp/texture.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "harness/import/convert.h"
#include "harness/usda/temporary_files.h"

namespace obscura::harness::importer {

namespace {

std::optional<aiColor3D> colorOf(const aiMaterial& material, const char* key, unsigned type, unsigned index) {
    aiColor3D color;
    if (material.Get(key, type, index, color) != aiReturn_SUCCESS) return std::nullopt;
    return color;
}

std::optional<float> scalarOf(const aiMaterial& material, const char* key, unsigned type, unsigned index) {
    float value = 0;
    if (material.Get(key, type, index, value) != aiReturn_SUCCESS) return std::nullopt;
    return value;
}

// Roughness, from the first of:
//  - the PBR roughness factor (glTF; FBX too, where Assimp derives it from the shininess exponent n
//    as Blender does, 1 - sqrt(n) / 10, which inverts Blender's FBX export);
//  - 1 - glossiness (glTF's specular-glossiness materials);
//  - a Phong exponent n (OBJ's Ns): Phong's lobe matches a microfacet alpha of sqrt(2 / (n + 2))
//    (Walter et al. 2007), and UsdPreviewSurface squares roughness into alpha, so
//    roughness = (2 / (n + 2))^(1/4).
std::optional<float> roughnessOf(const aiMaterial& material) {
    if (const auto roughness = scalarOf(material, AI_MATKEY_ROUGHNESS_FACTOR)) return roughness;
    if (const auto glossiness = scalarOf(material, AI_MATKEY_GLOSSINESS_FACTOR)) return 1.0f - *glossiness;
    if (const auto shininess = scalarOf(material, AI_MATKEY_SHININESS))
        return static_cast<float>(std::pow(2.0 / (std::max(*shininess, 0.0f) + 2.0), 0.25));
    return std::nullopt;
}

std::optional<aiColor3D> emissiveOf(const aiMaterial& material) {
    std::optional<aiColor3D> emissive = colorOf(material, AI_MATKEY_COLOR_EMISSIVE);
    if (const auto intensity = scalarOf(material, AI_MATKEY_EMISSIVE_INTENSITY); emissive && intensity)
        *emissive = *emissive * *intensity;
    return emissive;
}

// An image embedded in the file (glTF's data: URIs and buffer views, GLB, FBX) written out once per
// process (usda::temporaryFile), so the delegate reads it like any texture file. Assimp keeps such
// images as the file's bytes (mHeight 0, the format in achFormatHint); decoded texels it would
// have to re-encode are not written.
std::optional<std::string> embeddedTexture(const Source& source, const aiTexture& texture, const std::string& name,
                                           const std::string& label, Warnings& warnings) {
    if (texture.mHeight != 0) {
        warnings.add(label + ": embedded texture " + name + " is stored decoded; base colour texture ignored");
        return std::nullopt;
    }
    std::string extension = texture.achFormatHint[0] ? texture.achFormatHint : "bin";
    std::string error;
    std::string path = usda::temporaryFile(
        source.file.generic_string() + "#" + name, "embedded." + extension,
        [&](std::string*) -> std::optional<std::string> {
            return std::string(reinterpret_cast<const char*>(texture.pcData), texture.mWidth);
        },
        &error);
    if (path.empty()) {
        warnings.add(label + ": embedded texture " + name + ": " + error + "; base colour texture ignored");
        return std::nullopt;
    }
    std::optional<std::string> asset = assetPath(path);
    if (!asset) warnings.add(label + ": embedded texture " + name + " cannot be written as an asset path; ignored");
    return asset;
}

// The base colour texture as an absolute asset path (relative paths are relative to the imported
// file); nullopt when there is none or it cannot be referenced.
std::optional<std::string> baseColorTexture(const Source& source, const aiMaterial& material, const std::string& label,
                                            Warnings& warnings) {
    aiString file;
    if (material.GetTexture(aiTextureType_BASE_COLOR, 0, &file) != aiReturn_SUCCESS &&
        material.GetTexture(aiTextureType_DIFFUSE, 0, &file) != aiReturn_SUCCESS)
        return std::nullopt;
    if (const aiTexture* embedded = source.scene.GetEmbeddedTexture(file.C_Str())) return embeddedTexture(
        source, *embedded, file.C_Str(), label, warnings);
    // Files written on Windows separate folders with backslashes.
    std::string written = file.C_Str();
    std::replace(written.begin(), written.end(), '\\', '/');
    std::filesystem::path path(written);
    if (path.is_relative()) path = (source.file.parent_path() / path).lexically_normal();
    std::optional<std::string> asset = assetPath(path.generic_string());
    if (!asset) warnings.add(label + ": texture path '" + written + "' cannot be written as an asset path; ignored");
    return asset;
}

std::string colorText(const aiColor3D& c) { return tuple({c.r, c.g, c.b}); }

// Inputs of the Surface shader: what the material states, non-finite values left out.
class SurfaceInputs {
public:
    SurfaceInputs(const std::string& label, UsdaWriter& out, Warnings& warnings)
        : label_(label), out_(out), warnings_(warnings) {}

    void color(const std::string& input, const std::optional<aiColor3D>& value) {
        if (!value) return;
        if (isFinite(*value)) {
            out_.property("color3f inputs:" + input, colorText(*value));
        } else {
            warnings_.add(label_ + ": non-finite " + input + " dropped");
        }
    }

    void scalar(const std::string& input, const std::optional<float>& value) {
        if (!value) return;
        if (std::isfinite(*value)) {
            out_.property("float inputs:" + input, number(*value));
        } else {
            warnings_.add(label_ + ": non-finite " + input + " dropped");
        }
    }

private:
    const std::string& label_;
    UsdaWriter& out_;
    Warnings& warnings_;
};

// UsdUVTexture reading `asset` at the mesh's st, scaled by `factor` (glTF multiplies its base colour
// texture by the base colour factor).
void writeTextureShaders(const std::string& materialPath, const std::string& asset,
                         const std::optional<aiColor3D>& factor, UsdaWriter& out) {
    out.beginPrim("Shader", "BaseColorTexture");
    out.property("uniform token info:id", stringLiteral("UsdUVTexture"));
    out.property("asset inputs:file", asset);
    out.property("float2 inputs:st.connect", pathRef(materialPath + "/TexCoordReader.outputs:result"));
    if (factor) out.property("float4 inputs:scale", tuple({factor->r, factor->g, factor->b, 1.0f}));
    out.declare("float3 outputs:rgb");
    out.endPrim();
    out.beginPrim("Shader", "TexCoordReader");
    out.property("uniform token info:id", stringLiteral("UsdPrimvarReader_float2"));
    out.property("string inputs:varname", stringLiteral("st"));
    out.declare("float2 outputs:result");
    out.endPrim();
}

MaterialBinding writeMaterial(const Source& source, const aiMaterial& material, const std::string& path,
                              UsdaWriter& out, Warnings& warnings) {
    const std::string label = "material '" + std::string(material.GetName().C_Str()) + "'";
    // PBR files state a base colour, which multiplies the texture; Phong files a diffuse colour,
    // which the texture replaces.
    const std::optional<aiColor3D> baseColor = colorOf(material, AI_MATKEY_BASE_COLOR);
    const std::optional<aiColor3D> diffuse = baseColor ? baseColor : colorOf(material, AI_MATKEY_COLOR_DIFFUSE);
    const std::optional<std::string> texture = baseColorTexture(source, material, label, warnings);

    out.property("token outputs:surface.connect", pathRef(path + "/Surface.outputs:surface"));
    out.beginPrim("Shader", "Surface");
    out.property("uniform token info:id", stringLiteral("UsdPreviewSurface"));
    SurfaceInputs inputs(label, out, warnings);
    inputs.color("diffuseColor", diffuse);
    if (texture) out.property("color3f inputs:diffuseColor.connect", pathRef(path + "/BaseColorTexture.outputs:rgb"));
    inputs.scalar("metallic", scalarOf(material, AI_MATKEY_METALLIC_FACTOR));
    inputs.scalar("roughness", roughnessOf(material));
    inputs.color("emissiveColor", emissiveOf(material));
    inputs.scalar("opacity", scalarOf(material, AI_MATKEY_OPACITY));
    out.declare("token outputs:surface");
    out.endPrim();
    if (texture) writeTextureShaders(path, *texture, baseColor && isFinite(*baseColor) ? baseColor : std::nullopt, out);

    int twoSided = 0;
    material.Get(AI_MATKEY_TWOSIDED, twoSided);
    return {path, twoSided != 0};
}

}  // namespace

std::vector<MaterialBinding> writeMaterials(const Source& source, const std::string& looksPath, UsdaWriter& out,
                                            Warnings& warnings) {
    std::vector<MaterialBinding> bindings;
    NameScope names;
    for (unsigned i = 0; i < source.scene.mNumMaterials; ++i) {
        const aiMaterial& material = *source.scene.mMaterials[i];
        const std::string name = names.claim(material.GetName().C_Str(), "Material");
        out.beginPrim("Material", name);
        bindings.push_back(writeMaterial(source, material, looksPath + "/" + name, out, warnings));
        out.endPrim();
    }
    return bindings;
}

}  // namespace obscura::harness::importer
