// libFuzzer target: the glTF / OBJ import path (Assimp, the data-URI check, conversion to USD
// text) and the stage composed from what it writes. The first byte picks the format.
//
// The import runs as the harness runs it, in a child process: Assimp 5 still crashes on some
// malformed files, and that must be an error, not the end of the host. A crash outside Assimp's
// reader is a finding. Inputs Assimp reads are imported once more in this process, so that the
// conversion's coverage guides the fuzzer and its sanitizer reports stop it; both imports must agree.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "harness/import/assimp_to_usda.h"
#include "harness/usda/stage.h"

namespace {

[[noreturn]] void finding(const char* what, const std::string& detail) {
    std::fprintf(stderr, "%s: %s\n", what, detail.c_str());
    __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace obscura::harness;
    if (size < 1) return 0;
    static const char* const kExtensions[] = {".gltf", ".obj"};
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("obscura-fuzz-" + std::to_string(getpid()) + kExtensions[data[0] % 2]);
    std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    const auto isolated = importWithAssimp(file);
    if (const auto* error = std::get_if<ImportError>(&isolated)) {
        std::filesystem::remove(file);
        if (error->crash == ImportError::Crash::InConversion) finding("the import crashed outside Assimp", error->message);
        return 0;
    }
    const auto inProcess = importInThisProcess(file);
    std::filesystem::remove(file);
    const auto* result = std::get_if<ImportResult>(&inProcess);
    if (!result || result->usda != std::get<ImportResult>(isolated).usda ||
        result->warnings != std::get<ImportResult>(isolated).warnings)
        finding("the import in a child process and in this one disagree", file.string());
    auto stage = obscura::usda::Stage::openFromString(result->usda, file.string());
    // The importer writes USD text the reader must accept.
    if (auto* error = std::get_if<obscura::usda::Error>(&stage)) finding("imported text does not compose", error->str());
    return 0;
}
