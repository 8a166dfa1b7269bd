#include "harness/usda/temporary_files.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <mutex>

namespace obscura::usda {
namespace {

// The process the folder belongs to, fixed when the program starts: a forked child, whose pid
// differs, still writes into its parent's folder.
const pid_t kFolderOwner = ::getpid();

class TemporaryFiles {
public:
    ~TemporaryFiles() {
        std::error_code ec;
        if (::getpid() == kFolderOwner) std::filesystem::remove_all(folder(), ec);
    }

    std::string fileOf(const std::string& key, const std::string& fileName,
                       const std::function<std::optional<std::string>(std::string*)>& bytes, std::string* error) {
        std::lock_guard lock(mutex_);
        if (const auto it = files_.find(key); it != files_.end()) return it->second;
        auto contents = bytes(error);
        if (!contents) return "";
        // A folder per key keeps the file's name; the writer's pid keeps a child's apart from its parent's.
        std::error_code ec;
        const auto dir = folder() / (std::to_string(::getpid()) + "-" + std::to_string(written_++));
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

    std::map<std::string, std::string> byKey() {
        std::lock_guard lock(mutex_);
        return files_;
    }

    void adopt(const std::map<std::string, std::string>& files) {
        std::lock_guard lock(mutex_);
        files_.insert(files.begin(), files.end());
    }

private:
    static std::filesystem::path folder() {
        std::error_code ec;
        return std::filesystem::temp_directory_path(ec) / ("obscura-files-" + std::to_string(kFolderOwner));
    }

    std::mutex mutex_;
    size_t written_ = 0;
    std::map<std::string, std::string> files_;
};

// Made when the program starts, so that the folder's owner always removes it at exit, also when
// only its children wrote there.
TemporaryFiles gFiles;

}  // namespace

std::string temporaryFile(const std::string& key, const std::string& fileName,
                          const std::function<std::optional<std::string>(std::string* error)>& bytes,
                          std::string* error) {
    return gFiles.fileOf(key, fileName, bytes, error);
}

std::map<std::string, std::string> temporaryFilesByKey() { return gFiles.byKey(); }

void adoptTemporaryFiles(const std::map<std::string, std::string>& adopted) { gFiles.adopt(adopted); }

}  // namespace obscura::usda
