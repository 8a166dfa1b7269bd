#include "harness/usda/usdz_package.h"

#include "harness/usda/temporary_files.h"
#include "schemas/udim_pattern.h"

#include <zip.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace obscura::usda {

namespace {

// Larger files inside a package are refused rather than read into memory.
constexpr zip_uint64_t kMaxEntryBytes = zip_uint64_t(1) << 31;

bool isLayerFile(std::string name) {
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return name.ends_with(".usd") || name.ends_with(".usda") || name.ends_with(".usdc");
}

std::string extractPackagedUdimSet(const std::string& packagePattern, const std::string& archive,
                                   const std::string& pattern, std::string* error) {
    return temporaryFolder(packagePattern, pattern, [&](std::string* problem) -> std::optional<NamedFiles> {
        auto package = UsdzPackage::openFile(archive, problem);
        if (!package) return std::nullopt;
        NamedFiles tiles;
        for (const std::string& entry : package->entries()) {
            if (!schema::udimTileNumber(pattern, entry)) continue;
            auto bytes = package->read(entry, problem);
            if (!bytes) return std::nullopt;
            tiles.emplace(entry, std::move(*bytes));
        }
        if (tiles.empty()) {
            *problem = "no UDIM tile of '" + pattern + "' in the package";
            return std::nullopt;
        }
        return tiles;
    }, error);
}

}  // namespace

std::optional<std::pair<std::string, std::string>> splitPackagePath(std::string_view path) {
    if (!path.ends_with(']')) return std::nullopt;
    // The innermost package is the outermost bracket's content; nested packages are not read.
    const size_t open = path.find('[');
    if (open == std::string_view::npos || open == 0) return std::nullopt;
    return std::pair{std::string(path.substr(0, open)), std::string(path.substr(open + 1, path.size() - open - 2))};
}

std::string joinPackagePath(const std::string& archive, const std::string& entry) { return archive + "[" + entry + "]"; }

std::string extractPackagedFile(const std::string& packagePath, std::string* error) {
    const auto parts = splitPackagePath(packagePath);
    if (!parts) {
        *error = "'" + packagePath + "' names no file in a package";
        return "";
    }
    if (schema::isUdimPattern(parts->second)) return extractPackagedUdimSet(packagePath, parts->first, parts->second, error);
    return temporaryFile(packagePath, parts->second, [&](std::string* problem) -> std::optional<std::string> {
        auto package = UsdzPackage::openFile(parts->first, problem);
        if (!package) return std::nullopt;
        return package->read(parts->second, problem);
    }, error);
}

std::unique_ptr<UsdzPackage> UsdzPackage::openFile(const std::string& path, std::string* error) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (!in) {
        *error = "cannot open package '" + path + "'";
        return nullptr;
    }
    return open(bytes.str(), error);
}

std::unique_ptr<UsdzPackage> UsdzPackage::open(std::string bytes, std::string* error) {
    std::unique_ptr<UsdzPackage> package(new UsdzPackage());
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
    const zip_int64_t count = zip_get_num_entries(package->archive_, 0);
    for (zip_int64_t i = 0; i < count; ++i) {
        const char* name = zip_get_name(package->archive_, static_cast<zip_uint64_t>(i), 0);
        if (name && isLayerFile(name)) {
            package->rootLayer_ = name;
            break;
        }
    }
    return package;
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

}  // namespace obscura::usda
