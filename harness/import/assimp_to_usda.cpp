#include "harness/import/assimp_to_usda.h"

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>

#include "harness/import/convert.h"
#include "harness/import/gltf_data_uris.h"

namespace obscura::harness {

namespace {

using importer::SourceFormat;

// Polygons are kept as they are (no triangulation) and identical corners are merged so that each
// vertex is written once. aiProcess_SortByPType is left out: it would split a mesh that mixes
// triangles and larger polygons in two; point and line primitives are dropped when writing instead.
// Validation rejects corrupt data (out-of-range indices, missing arrays) before conversion.
constexpr unsigned kPostProcess = aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure;

std::string lowerCaseExtension(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

std::optional<SourceFormat> formatOf(const std::filesystem::path& file) {
    const std::string extension = lowerCaseExtension(file);
    if (extension == ".gltf" || extension == ".glb") return SourceFormat::Gltf;
    if (extension == ".fbx") return SourceFormat::Fbx;
    if (extension == ".obj") return SourceFormat::Obj;
    return std::nullopt;
}

// Assimp offers a file to the readers of its extension and then to every reader that recognises
// its first bytes: a .gltf starting with a Quick3D header went to the Quick3D reader, which
// crashed on it (tests/import/data/quick3d_header.gltf). Only the readers of the file's own
// extension stay registered; Assimp deletes only the readers it still holds, so the others are
// deleted here.
void keepOnlyReadersOf(Assimp::Importer& reader, const std::string& extension) {
    for (size_t i = reader.GetImporterCount(); i-- > 0;) {
        const aiImporterDesc* info = reader.GetImporterInfo(i);
        std::istringstream extensions(info && info->mFileExtensions ? info->mFileExtensions : "");
        bool reads = false;
        for (std::string listed; extensions >> listed;) reads = reads || "." + listed == extension;
        if (reads) continue;
        std::unique_ptr<Assimp::BaseImporter> other(reader.GetImporter(i));
        if (reader.UnregisterLoader(other.get()) != AI_SUCCESS) other.release();
    }
}

std::optional<double> metadataNumber(const aiScene& scene, const char* key) {
    const aiMetadata* metadata = scene.mMetaData;
    if (!metadata) return std::nullopt;
    for (unsigned i = 0; i < metadata->mNumProperties; ++i) {
        if (metadata->mKeys[i] != aiString(key)) continue;
        const aiMetadataEntry& entry = metadata->mValues[i];
        switch (entry.mType) {
        case AI_INT32: return *static_cast<const int32_t*>(entry.mData);
        case AI_UINT64: return static_cast<double>(*static_cast<const uint64_t*>(entry.mData));
        case AI_FLOAT: return *static_cast<const float*>(entry.mData);
        case AI_DOUBLE: return *static_cast<const double*>(entry.mData);
        default: return std::nullopt;
        }
    }
    return std::nullopt;
}

// glTF is in metres by definition; FBX states its unit in centimetres (UnitScaleFactor, 1 when
// absent); OBJ has no units.
double metersPerUnit(const aiScene& scene, SourceFormat format, importer::Warnings& warnings) {
    switch (format) {
    case SourceFormat::Gltf: return 1.0;
    case SourceFormat::Fbx: {
        const std::optional<double> centimetres = metadataNumber(scene, "UnitScaleFactor");
        if (!centimetres) return 0.01;
        if (*centimetres > 0 && std::isfinite(*centimetres)) return *centimetres / 100.0;
        warnings.add("FBX UnitScaleFactor is not a positive number; centimetres assumed");
        return 0.01;
    }
    case SourceFormat::Obj: warnings.add("OBJ files carry no units; metres assumed"); return 1.0;
    }
    return 1.0;
}

// FBX files name their axes (up, front, and the third, "coord", each an axis index and a sign);
// Assimp keeps the file's coordinates. The rotation taking them to USD's Y up, Z front, X right,
// or nullopt when the file is already so or does not say. Left-handed systems would need a mirror
// and are left as they are.
std::optional<aiMatrix4x4> fbxAxisCorrection(const aiScene& scene, importer::Warnings& warnings) {
    const char* keys[3][2] = {{"CoordAxis", "CoordAxisSign"}, {"UpAxis", "UpAxisSign"}, {"FrontAxis", "FrontAxisSign"}};
    aiMatrix4x4 rotation;
    bool used[3] = {false, false, false};
    for (unsigned row = 0; row < 3; ++row) {
        const std::optional<double> axis = metadataNumber(scene, keys[row][0]);
        const std::optional<double> sign = metadataNumber(scene, keys[row][1]);
        if (!axis || !sign) return std::nullopt;
        const bool isAxis = *axis == 0 || *axis == 1 || *axis == 2;
        const int column = isAxis ? static_cast<int>(*axis) : 0;
        if (!isAxis || used[column] || std::abs(*sign) != 1.0) {
            warnings.add("FBX axis system is not valid; axes left as in the file");
            return std::nullopt;
        }
        used[column] = true;
        for (int c = 0; c < 3; ++c) rotation[row][c] = c == column ? static_cast<float>(*sign) : 0.0f;
    }
    if (rotation.Determinant() < 0) {
        warnings.add("FBX axis system is left-handed; axes left as in the file");
        return std::nullopt;
    }
    if (rotation.IsIdentity()) return std::nullopt;
    return rotation;
}

std::vector<std::string> layerMetadata(const importer::Source& source, const importer::Timeline& timeline) {
    using importer::number;
    using importer::stringLiteral;
    std::vector<std::string> items = {
        "defaultPrim = \"Root\"",
        "doc = " + stringLiteral("Imported from " + source.file.filename().string() + " through Assimp"),
        "upAxis = \"Y\"",
        // Assimp holds FBX's unit as a float: written at that precision, 2.54 cm is 0.0254 and not
        // 0.025399999618530275.
        "metersPerUnit = " + number(static_cast<float>(source.metersPerUnit)),
        "timeCodesPerSecond = " + number(timeline.ticksPerSecond),
    };
    if (timeline.range) {
        items.push_back("startTimeCode = " + number(timeline.range->first));
        items.push_back("endTimeCode = " + number(timeline.range->second));
    }
    return items;
}

std::string convert(const importer::Source& source, importer::Warnings& warnings) {
    const importer::Timeline timeline = importer::readTimeline(source.scene, warnings);
    const std::optional<aiMatrix4x4> correction =
        source.format == SourceFormat::Fbx ? fbxAxisCorrection(source.scene, warnings) : std::nullopt;
    importer::UsdaWriter out(layerMetadata(source, timeline));
    // UsdSkel skins only beneath a SkelRoot.
    const bool skinned = importer::hasSkinnedMeshes(source.scene);
    out.beginPrim(skinned ? "SkelRoot" : "Xform", "Root");
    importer::NameScope rootNames;
    const std::string looks = rootNames.claim("Looks", "Looks");
    out.beginPrim("Scope", looks);
    const std::vector<importer::MaterialBinding> materials =
        importer::writeMaterials(source, "/Root/" + looks, out, warnings);
    out.endPrim();
    std::map<const aiMesh*, std::string> skeletons;
    if (skinned) {
        const std::string scope = rootNames.claim("Skeletons", "Skeletons");
        out.beginPrim("Scope", scope);
        skeletons = importer::writeSkeletons(source, timeline, "/Root/" + scope, out, warnings);
        out.endPrim();
    }
    importer::writeRootContents(source, timeline, materials, skeletons, correction, rootNames, out, warnings);
    out.endPrim();
    return out.text();
}

}  // namespace

bool isAssimpFormat(const std::filesystem::path& file) { return formatOf(file).has_value(); }

std::variant<ImportResult, ImportError> importInThisProcess(const std::filesystem::path& file,
                                                            const std::function<void(ImportStep)>& onStep) {
    const std::optional<SourceFormat> format = formatOf(file);
    if (!format) return ImportError{file.string() + ": not a format imported through Assimp (.gltf, .glb, .fbx, .obj)"};
    if (std::string problem = checkGltfDataUris(file); !problem.empty()) return ImportError{problem};
    Assimp::Importer reader;
    keepOnlyReadersOf(reader, lowerCaseExtension(file));
    // FBX pivots and pre-rotations are folded into each node's transform rather than added as
    // "$AssimpFbx$" helper nodes, so animation channels target the nodes the file names.
    reader.SetPropertyBool(AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS, false);
    if (onStep) onStep(ImportStep::ReaderStarts);
    const aiScene* scene = reader.ReadFile(file.string(), kPostProcess);
    if (onStep) onStep(ImportStep::ReaderReturned);
    if (!scene || !scene->mRootNode)
        return ImportError{"cannot import " + file.string() + ": " + reader.GetErrorString()};

    importer::Warnings warnings;
    if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) warnings.add("Assimp reports the scene as incomplete");
    const importer::Source source{*scene, std::filesystem::absolute(file), *format,
                                  metersPerUnit(*scene, *format, warnings)};
    ImportResult result;
    result.usda = convert(source, warnings);
    result.warnings = warnings.take();
    return result;
}

}  // namespace obscura::harness
