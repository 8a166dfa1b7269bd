#include "assets/usdz_package.h"

#include <zip.h>

#include <algorithm>

namespace obscura::assets {

namespace {

// Larger files inside a package are refused rather than read into memory.
constexpr zip_uint64_t kMaxEntryBytes = zip_uint64_t(1) << 31;

bool isLayerFile(std::string name) {
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return name.ends_with(".usd") || name.ends_with(".usda") || name.ends_with(".usdc");
}

}  // namespace

std::unique_ptr<UsdzPackage> UsdzPackage::openFile(const std::string& path, std::string* error) {
    int code = ZIP_ER_OK;
    ::zip* archive = zip_open(path.c_str(), ZIP_RDONLY, &code);
    if (!archive) {
        zip_error_t zipError;
        zip_error_init_with_code(&zipError, code);
        // Worded as open() and a plain file's read word theirs: the caller names the path.
        *error = code == ZIP_ER_NOENT ? std::string("no such file")
                                      : std::string("not a readable zip archive: ") + zip_error_strerror(&zipError);
        zip_error_fini(&zipError);
        return nullptr;
    }
    std::unique_ptr<UsdzPackage> package(new UsdzPackage());
    package->archive_ = archive;
    package->findRootLayer();
    return package;
}

std::unique_ptr<UsdzPackage> UsdzPackage::open(std::string bytes, std::string* error) {
    std::unique_ptr<UsdzPackage> package(new UsdzPackage());
    // libzip reads the bytes where they lie: in the package, which outlives the archive.
    package->bytes_ = std::move(bytes);
    zip_error_t zipError;
    zip_error_init(&zipError);
    zip_source_t* source = zip_source_buffer_create(package->bytes_.data(), package->bytes_.size(), 0, &zipError);
    if (source) package->archive_ = zip_open_from_source(source, ZIP_RDONLY, &zipError);
    if (!package->archive_) {
        *error = std::string("not a readable zip archive: ") + zip_error_strerror(&zipError);
        if (source) zip_source_free(source);
        zip_error_fini(&zipError);
        return nullptr;
    }
    zip_error_fini(&zipError);
    package->findRootLayer();
    return package;
}

void UsdzPackage::findRootLayer() {
    const zip_int64_t count = zip_get_num_entries(archive_, 0);
    for (zip_int64_t i = 0; i < count; ++i) {
        const char* name = zip_get_name(archive_, static_cast<zip_uint64_t>(i), 0);
        if (name && isLayerFile(name)) {
            rootLayer_ = name;
            return;
        }
    }
}

UsdzPackage::~UsdzPackage() {
    if (archive_) zip_discard(archive_);
}

std::optional<std::string> UsdzPackage::read(const std::string& entry, std::string* error) const {
    const zip_int64_t index = zip_name_locate(archive_, entry.c_str(), 0);
    zip_stat_t stat;
    if (index < 0 || zip_stat_index(archive_, static_cast<zip_uint64_t>(index), 0, &stat) != 0) {
        *error = "no file '" + entry + "' in the package";
        return std::nullopt;
    }
    if (!(stat.valid & ZIP_STAT_SIZE) || stat.size > kMaxEntryBytes) {
        *error = "file '" + entry + "' in the package is too large";
        return std::nullopt;
    }
    zip_file_t* file = zip_fopen_index(archive_, static_cast<zip_uint64_t>(index), 0);
    if (!file) {
        *error = "cannot read '" + entry + "' from the package: " + zip_strerror(archive_);
        return std::nullopt;
    }
    std::string bytes(stat.size, '\0');
    const zip_int64_t got = zip_fread(file, bytes.data(), stat.size);
    zip_fclose(file);
    if (got < 0 || static_cast<zip_uint64_t>(got) != stat.size) {
        *error = "file '" + entry + "' in the package is truncated or corrupt";
        return std::nullopt;
    }
    return bytes;
}

std::vector<std::string> UsdzPackage::entries() const {
    std::vector<std::string> names;
    const zip_int64_t count = zip_get_num_entries(archive_, 0);
    for (zip_int64_t i = 0; i < count; ++i)
        if (const char* name = zip_get_name(archive_, static_cast<zip_uint64_t>(i), 0)) names.emplace_back(name);
    return names;
}

}  // namespace obscura::assets
