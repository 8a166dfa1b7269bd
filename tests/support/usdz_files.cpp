#include "tests/support/usdz_files.h"

#include <zip.h>

#include <fstream>
#include <sstream>

namespace obscura::test {

std::string writeUsdz(const std::filesystem::path& archive, const PackageFiles& files) {
    std::error_code ec;
    std::filesystem::create_directories(archive.parent_path(), ec);
    int code = ZIP_ER_OK;
    zip_t* zip = zip_open(archive.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
    if (!zip) return "zip_open failed with libzip error " + std::to_string(code);
    for (const auto& [name, bytes] : files) {
        // libzip reads the contents when the archive is closed; `files` outlives that.
        zip_source_t* source = zip_source_buffer(zip, bytes.data(), bytes.size(), 0);
        const zip_int64_t index = source ? zip_file_add(zip, name.c_str(), source, ZIP_FL_OVERWRITE) : -1;
        if (index < 0 || zip_set_file_compression(zip, zip_uint64_t(index), ZIP_CM_STORE, 0) != 0) {
            const std::string reason = std::string("adding ") + name + ": " + zip_strerror(zip);
            if (source && index < 0) zip_source_free(source);
            zip_discard(zip);
            return reason;
        }
    }
    if (zip_close(zip) != 0) {
        const std::string reason = std::string("zip_close: ") + zip_strerror(zip);
        zip_discard(zip);
        return reason;
    }
    return "";
}

std::string fileBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

}  // namespace obscura::test
