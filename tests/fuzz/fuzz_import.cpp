// libFuzzer target: the glTF / OBJ import path (Assimp, the data-URI check, conversion to USD
// text) and the stage composed from what it writes. The first byte picks the format.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "harness/import/assimp_to_usda.h"
#include "harness/usda/stage.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    static const char* const kExtensions[] = {".gltf", ".obj"};
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("obscura-fuzz-" + std::to_string(getpid()) + kExtensions[data[0] % 2]);
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    auto imported = obscura::harness::importWithAssimp(file);
    std::filesystem::remove(file);
    if (auto* result = std::get_if<obscura::harness::ImportResult>(&imported)) {
        auto stage = obscura::usda::Stage::openFromString(result->usda, file.string());
        // The importer writes USD text the reader must accept.
        if (auto* error = std::get_if<obscura::usda::Error>(&stage)) {
            std::fprintf(stderr, "imported text does not compose: %s\n", error->str().c_str());
            __builtin_trap();
        }
    }
    return 0;
}
