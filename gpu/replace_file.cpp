#include "gpu/replace_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>

namespace obscura::gpu {

bool replaceFile(const std::filesystem::path& file, const void* data, size_t size) {
    std::error_code error;
    std::filesystem::create_directories(file.parent_path(), error);
    // The process id and a count within the process keep concurrent writers of the same file apart
    // (two delegates of one process may save the same device's pipelines at once).
    static std::atomic<uint64_t> writes{0};
    const std::filesystem::path temporary =
        file.string() + ".tmp" + std::to_string(getpid()) + "-" + std::to_string(writes.fetch_add(1));
    {
        std::ofstream out(temporary, std::ios::binary);
        out.write(static_cast<const char*>(data), std::streamsize(size));
        if (!out) {
            std::filesystem::remove(temporary, error);
            return false;
        }
    }
    std::filesystem::rename(temporary, file, error);
    if (!error) return true;
    std::filesystem::remove(temporary, error);
    return false;
}

std::optional<std::vector<char>> readWholeFile(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt;
    return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace obscura::gpu
