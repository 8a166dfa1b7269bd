// glTF buffers and images may embed their bytes as base64 data URIs (glTF 2.0, section 3.6.1).
// Assimp decodes a corrupt one into garbage without a word; the harness checks them first.
#pragma once

#include <filesystem>
#include <string>

namespace obscura::harness {

// "" when every data URI of the .gltf file is valid base64 holding at least the buffer's
// byteLength; else "file:line:column: buffers[0].uri: ..." naming the first problem. Files that
// are not JSON (.glb) are left to Assimp.
std::string checkGltfDataUris(const std::filesystem::path& file);

}  // namespace obscura::harness
