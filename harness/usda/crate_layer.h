// A crate file's specs as the same layer model the text reader fills (layer.h), so that
// composition treats text and binary layers alike. Spec paths and fields follow Sdf's data
// model (pxr/usd/sdf/schema.h field names: specifier, typeName, primChildren, default, ...).
#pragma once

#include <memory>
#include <span>
#include <string>

#include "harness/usda/layer.h"

namespace obscura::usda {

// Reads a crate file; throws crate::Failure for malformed data.
std::unique_ptr<Layer> readCrateLayer(std::span<const char> bytes, const std::string& identifier);

}  // namespace obscura::usda
