// Spline values (type Spline) of a crate file, OpenUSD 25.05's TsSpline. The crate stores one as a
// uint64 byte count and that many bytes of Ts's binary form, then the knots' custom data
// (crateFile.cpp, _Reader::Read<TsSpline>); the bytes are laid out by pxr/base/ts/binary.cpp.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "harness/usda/crate_compression.h"
#include "harness/usda/spline.h"

namespace obscura::usda::crate {

// The spline stored at byte `at` of `bytes`, for an attribute of scalar type `valueType`;
// throws Failure at the byte where it is malformed or of a binary version not read here.
std::shared_ptr<const Spline> decodeSpline(std::span<const char> bytes, uint64_t at, const std::string& valueType);

}  // namespace obscura::usda::crate
