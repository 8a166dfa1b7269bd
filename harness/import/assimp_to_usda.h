// Scenes in glTF 2.0 (.gltf, .glb), FBX and OBJ, read through Assimp and written as one USD text
// layer, so the harness composes them with usda::Stage::openFromString like any .usda scene.
//
// The layer is Y-up with a "Root" default prim holding the node hierarchy (Xforms with
// xformOp:transform, or translate/orient/scale time samples for animated nodes), polygon meshes,
// UsdPreviewSurface materials under Root/Looks, cameras and UsdLux lights. Asset paths are absolute,
// so the text does not depend on the path it is opened under; pass the imported file's path anyway
// so that diagnostics name it.
#pragma once

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace obscura::harness {

struct ImportResult {
    std::string usda;
    std::vector<std::string> warnings;  // what was dropped or approximated, one line each
};

struct ImportError {
    std::string message;  // names the file and Assimp's reason
};

// .gltf, .glb, .fbx and .obj, in any letter case.
bool isAssimpFormat(const std::filesystem::path& file);

std::variant<ImportResult, ImportError> importWithAssimp(const std::filesystem::path& file);

}  // namespace obscura::harness
