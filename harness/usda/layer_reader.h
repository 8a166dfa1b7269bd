// Reads one layer from its bytes, choosing the format by content rather than by extension (a
// .usd file may be either): crate files start with "PXR-USDC", anything else is read as text.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <variant>

#include "harness/usda/layer.h"

namespace obscura::usda {

bool isCrateData(std::string_view bytes);
// A zip archive (a USDZ package): "PK\3\4".
bool isZipData(std::string_view bytes);

// Errors in crate files read "identifier: byte N: what".
std::variant<std::unique_ptr<Layer>, Error> readLayer(std::string_view bytes, const std::string& identifier);

}  // namespace obscura::usda
