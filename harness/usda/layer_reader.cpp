#include "harness/usda/layer_reader.h"

#include <span>

#include "harness/usda/crate_compression.h"
#include "harness/usda/crate_layer.h"
#include "harness/usda/usda_parser.h"

namespace obscura::usda {

bool isCrateData(std::string_view bytes) { return bytes.starts_with("PXR-USDC"); }

bool isZipData(std::string_view bytes) { return bytes.starts_with(std::string_view("PK\x03\x04", 4)); }

std::variant<std::unique_ptr<Layer>, Error> readLayer(std::string_view bytes, const std::string& identifier) {
    if (!isCrateData(bytes)) return parseLayer(bytes, identifier);
    try {
        return readCrateLayer(std::span<const char>(bytes.data(), bytes.size()), identifier);
    } catch (const crate::Failure& failure) {
        return Error{SourceLocation{identifier, 0, 0}, "byte " + std::to_string(failure.offset) + ": " + failure.message};
    } catch (const std::bad_alloc&) {
        return Error{SourceLocation{identifier, 0, 0}, "crate file needs more memory than is available"};
    }
}

}  // namespace obscura::usda
