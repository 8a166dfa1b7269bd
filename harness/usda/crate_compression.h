// Decoding of the compressed blocks of USD's binary crate format (.usdc): TfFastCompression's LZ4
// chunks (OpenUSD pxr/base/tf/fastCompression.cpp) and the integer coding that the structural
// sections and integer arrays use (pxr/usd/sdf/integerCoding.cpp). Every read is bounds-checked:
// malformed input throws crate::Failure naming the byte it concerns.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace obscura::usda::crate {

// Malformed or unsupported data at a byte offset of the file.
struct Failure {
    uint64_t offset;
    std::string message;
};

// TfFastCompression: a chunk-count byte (0: one LZ4 block filling the rest), then for each chunk
// an int32 size and an LZ4 block. Decodes at most `maxOutput` bytes; `at` is where the block
// starts in the file, for messages.
std::vector<char> decompressLz4(std::span<const char> compressed, size_t maxOutput, uint64_t at);

// Integer coding: the common delta (an Int), 2-bit codes per value (common, 8/16/32-bit delta
// for 32-bit ints; common, 16/32/64-bit for 64-bit ints), then the deltas; values are running
// sums of the deltas. `Int` is int32_t, uint32_t, int64_t or uint64_t.
template <class Int>
std::vector<Int> decodeIntegers(std::span<const char> encoded, size_t count, uint64_t at);

// LZ4 then integer decoding, as the crate stores index lists and compressed integer arrays.
template <class Int>
std::vector<Int> decompressIntegers(std::span<const char> compressed, size_t count, uint64_t at);

// The most values `compressedBytes` of coded integers can hold (LZ4 packs at most ~255 bytes
// into one, and the codes hold 4 values a byte): larger counts are corrupt, and refusing them
// keeps a bad count from allocating without bound.
constexpr uint64_t maxCodedIntegers(uint64_t compressedBytes) { return compressedBytes * 1024 + 1024; }

}  // namespace obscura::usda::crate
