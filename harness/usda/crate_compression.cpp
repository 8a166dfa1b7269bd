#include "harness/usda/crate_compression.h"

#include <lz4.h>

#include <cstring>
#include <type_traits>

namespace obscura::usda::crate {

std::vector<char> decompressLz4(std::span<const char> compressed, size_t maxOutput, uint64_t at) {
    if (compressed.empty()) throw Failure{at, "empty compressed block"};
    if (maxOutput > size_t(LZ4_MAX_INPUT_SIZE) * 127) throw Failure{at, "compressed block claims too large a size"};
    std::vector<char> out(maxOutput);
    const auto chunks = static_cast<unsigned char>(compressed[0]);
    size_t pos = 1;
    size_t written = 0;
    auto decode = [&](size_t size) {
        if (size > compressed.size() - pos) throw Failure{at + pos, "LZ4 chunk runs past the end of its section"};
        const size_t room = std::min<size_t>(out.size() - written, LZ4_MAX_INPUT_SIZE);
        const int n = LZ4_decompress_safe(compressed.data() + pos, out.data() + written, static_cast<int>(size),
                                          static_cast<int>(room));
        if (n < 0) throw Failure{at + pos, "corrupt LZ4 data (error " + std::to_string(n) + ")"};
        pos += size;
        written += static_cast<size_t>(n);
    };
    if (chunks == 0) {
        decode(compressed.size() - 1);
    } else {
        for (unsigned i = 0; i < chunks; ++i) {
            int32_t size = 0;
            if (compressed.size() - pos < sizeof(size)) throw Failure{at + pos, "LZ4 chunk size past the end of its section"};
            std::memcpy(&size, compressed.data() + pos, sizeof(size));
            pos += sizeof(size);
            if (size < 0) throw Failure{at + pos - sizeof(size), "negative LZ4 chunk size"};
            decode(static_cast<size_t>(size));
        }
    }
    out.resize(written);
    return out;
}

template <class Int>
std::vector<Int> decodeIntegers(std::span<const char> encoded, size_t count, uint64_t at) {
    // Arithmetic in the unsigned type: deltas of a corrupt stream may overflow, which wraps.
    using UInt = std::make_unsigned_t<Int>;
    using SInt = std::make_signed_t<Int>;
    using Small = std::conditional_t<sizeof(Int) == 4, int8_t, int16_t>;
    using Medium = std::conditional_t<sizeof(Int) == 4, int16_t, int32_t>;
    std::vector<Int> out;
    if (count == 0) return out;
    const size_t codeBytes = (count * 2 + 7) / 8;
    if (encoded.size() < sizeof(SInt) + codeBytes) throw Failure{at, "coded integers are shorter than their codes"};
    auto readAt = [&](size_t& pos, auto zero) {
        decltype(zero) value;
        if (encoded.size() - pos < sizeof(value)) throw Failure{at, "coded integers end before their values"};
        std::memcpy(&value, encoded.data() + pos, sizeof(value));
        pos += sizeof(value);
        return static_cast<UInt>(static_cast<SInt>(value));
    };
    size_t pos = 0;
    const UInt common = readAt(pos, SInt{});
    size_t codes = pos;
    size_t values = pos + codeBytes;
    out.reserve(count);
    UInt previous = 0;
    for (size_t i = 0; i < count; ++i) {
        const auto codeByte = static_cast<unsigned char>(encoded[codes + i / 4]);
        switch ((codeByte >> (2 * (i % 4))) & 3) {
        case 0: previous += common; break;
        case 1: previous += readAt(values, Small{}); break;
        case 2: previous += readAt(values, Medium{}); break;
        default: previous += readAt(values, SInt{}); break;
        }
        out.push_back(static_cast<Int>(previous));
    }
    return out;
}

template <class Int>
std::vector<Int> decompressIntegers(std::span<const char> compressed, size_t count, uint64_t at) {
    if (count > maxCodedIntegers(compressed.size()))
        throw Failure{at, std::to_string(count) + " integers cannot fit in " + std::to_string(compressed.size()) +
                              " compressed bytes"};
    if (count == 0) return {};
    const size_t encodedMax = sizeof(Int) + (count * 2 + 7) / 8 + count * sizeof(Int);
    const std::vector<char> encoded = decompressLz4(compressed, encodedMax, at);
    return decodeIntegers<Int>(encoded, count, at);
}

template std::vector<int32_t> decodeIntegers<int32_t>(std::span<const char>, size_t, uint64_t);
template std::vector<uint32_t> decodeIntegers<uint32_t>(std::span<const char>, size_t, uint64_t);
template std::vector<int64_t> decodeIntegers<int64_t>(std::span<const char>, size_t, uint64_t);
template std::vector<uint64_t> decodeIntegers<uint64_t>(std::span<const char>, size_t, uint64_t);
template std::vector<int32_t> decompressIntegers<int32_t>(std::span<const char>, size_t, uint64_t);
template std::vector<uint32_t> decompressIntegers<uint32_t>(std::span<const char>, size_t, uint64_t);
template std::vector<int64_t> decompressIntegers<int64_t>(std::span<const char>, size_t, uint64_t);
template std::vector<uint64_t> decompressIntegers<uint64_t>(std::span<const char>, size_t, uint64_t);

}  // namespace obscura::usda::crate
