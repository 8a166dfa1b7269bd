#include "tests/support/usdz_writer.h"

#include <zip.h>

namespace obscura::test {

std::string writePackage(const std::filesystem::path& archive, const PackageEntries& entries) {
    std::filesystem::create_directories(archive.parent_path());
    int error = 0;
    zip_t* zip = zip_open(archive.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    if (!zip) return "zip_open failed with libzip error " + std::to_string(error);
    for (const auto& [name, bytes] : entries) {
        zip_source_t* source = zip_source_buffer(zip, bytes.data(), bytes.size(), 0);
        const zip_int64_t index = source ? zip_file_add(zip, name.c_str(), source, ZIP_FL_OVERWRITE) : -1;
        if (index < 0 || zip_set_file_compression(zip, zip_uint64_t(index), ZIP_CM_STORE, 0) != 0) {
            if (source && index < 0) zip_source_free(source);
            const std::string why = name + ": " + zip_strerror(zip);
            zip_discard(zip);
            return why;
        }
    }
    if (zip_close(zip) != 0) {
        const std::string why = zip_strerror(zip);
        zip_discard(zip);
        return why;
    }
    return "";
}

}  // namespace obscura::test
