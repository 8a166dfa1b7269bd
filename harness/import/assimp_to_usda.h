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
#include <functional>
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
    // The import's process ended abnormally: while Assimp read the file (a reader's bug, met on a
    // malformed file), or while its scene was converted (a bug of ours).
    enum class Crash { None, InReader, InConversion } crash = Crash::None;
};

// .gltf, .glb, .fbx and .obj, in any letter case.
bool isAssimpFormat(const std::filesystem::path& file);

// Reads and converts in a child process (harness/import/child_server.h): Assimp 5 still crashes on
// some malformed files, and a crash there must be an error for the host, not its end.
std::variant<ImportResult, ImportError> importWithAssimp(const std::filesystem::path& file);

// The import's progress, for a caller watching it from another process: a crash between the two
// steps is Assimp's, anywhere else it is ours.
enum class ImportStep { ReaderStarts, ReaderReturned };

// The same import in this process, where a reader crash is this process's. onStep, if given, is
// told of each step as it is reached.
std::variant<ImportResult, ImportError> importInThisProcess(const std::filesystem::path& file,
                                                            const std::function<void(ImportStep)>& onStep = {});

}  // namespace obscura::harness
