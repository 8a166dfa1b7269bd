#include "harness/usda/temporary_files.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>

namespace obscura::usda {
namespace {

class TemporaryFiles {
public:
    ~TemporaryFiles() {
        std::error_code ec;
        if (!folder_.empty()) std::filesystem::remove_all(folder_, ec);
    }
    std::string file(const std::string& key, const std::string& fileName,
                     const std::function<std::optional<std::string>(std::string*)>& bytes, std::string* error) {
        std::lock_guard lock(mutex_);
        if (const auto it = files_.find(key); it != files_.end()) return it->second;
        auto contents = bytes(error);
        if (!contents) return "";
        std::error_code ec;
        if (folder_.empty()) {
            folder_ = std::filesystem::temp_directory_path(ec) / ("obscura-files-" + std::to_string(::getpid()));
            std::filesystem::create_directories(folder_, ec);
        }
        // One folder per file keeps its name.
        const auto dir = folder_ / std::to_string(files_.size());
        std::filesystem::create_directories(dir, ec);
        const auto path = dir / std::filesystem::path(fileName).filename();
        std::ofstream out(path, std::ios::binary);
        out.write(contents->data(), static_cast<std::streamsize>(contents->size()));
        if (!out) {
            *error = "cannot write '" + path.string() + "'";
            return "";
        }
        return files_[key] = path.string();
    }

private:
    std::mutex mutex_;
    std::filesystem::path folder_;
    std::map<std::string, std::string> files_;
};

}  // namespace

std::string temporaryFile(const std::string& key, const std::string& fileName,
                          const std::function<std::optional<std::string>(std::string* error)>& bytes,
                          std::string* error) {
    static TemporaryFiles files;
    return files.file(key, fileName, bytes, error);
}

}  // namespace obscura::usda
