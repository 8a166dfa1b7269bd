// Crate files built byte by byte for the reader's tests, as OpenUSD's crateFile.cpp lays them out.
#pragma once

#include <lz4.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "harness/usda/crate_file.h"

namespace obscura::usda::test {

// A crate file of version 0.12.0 laid out as crateFile.cpp writes one (bootstrap, values, the
// structural sections, the table of contents), holding prim </A> (its fields given) with attributes
// whose fields are given as ValueReps. Structural integers are coded at full width (code 3 each).
class CrateWriter {
public:
    using Fields = std::vector<std::pair<std::string, uint64_t>>;  // field name, ValueRep bits
    struct Attribute {
        std::string name;
        Fields fields;
    };

    static uint64_t inlined(crate::Type type, uint32_t payload) {
        return uint64_t(type) << 48 | uint64_t(1) << 62 | payload;
    }
    // Data placed after the bootstrap; a rep of `type` pointing at it.
    uint64_t stored(crate::Type type, const std::string& bytes) {
        const uint64_t at = 88 + values_.size();
        values_ += bytes;
        return uint64_t(type) << 48 | at;
    }
    uint32_t token(const std::string& name) {
        for (uint32_t i = 0; i < tokens_.size(); ++i)
            if (tokens_[i] == name) return i;
        tokens_.push_back(name);
        return uint32_t(tokens_.size() - 1);
    }
    // A string's index in the STRINGS section (which names tokens), as asset paths are written.
    uint32_t string(const std::string& text) {
        strings_.push_back(token(text));
        return uint32_t(strings_.size() - 1);
    }
    // The index of </A> in the PATHS section.
    static constexpr uint32_t kPrimA = 1;

    std::string write(const std::vector<Attribute>& attributes, const Fields& layerFields = {},
                      Fields primFields = {}) {
        // Specs: the pseudo-root, </A> (def) and its attributes, each with its run of fields.
        std::vector<uint32_t> fieldTokens, fieldSets, specPaths, specSets, specTypes;
        std::string reps;
        auto spec = [&](uint32_t path, uint32_t type, const Fields& fields) {
            specPaths.push_back(path);
            specSets.push_back(uint32_t(fieldSets.size()));
            specTypes.push_back(type);
            for (const auto& [name, rep] : fields) {
                fieldSets.push_back(uint32_t(fieldTokens.size()));
                fieldTokens.push_back(token(name));
                reps += raw(rep);
            }
            fieldSets.push_back(~0u);
        };
        spec(0, 7, layerFields);
        primFields.insert(primFields.begin(), {"specifier", inlined(crate::Type::Specifier, 0)});
        spec(kPrimA, 6, primFields);
        // Paths: "/", "/A", then the properties as siblings (jumps: -1 a child follows, 0 a sibling
        // follows, -2 neither); a property's element token is negated.
        std::vector<uint32_t> pathIndexes{0, 1};
        std::vector<uint32_t> elements{0, token("A")};
        std::vector<uint32_t> jumps{uint32_t(-1), uint32_t(-1)};
        for (size_t i = 0; i < attributes.size(); ++i) {
            const auto path = uint32_t(2 + i);
            spec(path, 1, attributes[i].fields);
            pathIndexes.push_back(path);
            elements.push_back(uint32_t(-int32_t(token(attributes[i].name))));
            jumps.push_back(i + 1 < attributes.size() ? 0 : uint32_t(-2));
        }
        std::string tokenChars;
        for (const std::string& t : tokens_) tokenChars += t + '\0';

        std::string file = "PXR-USDC" + std::string("\0\x0c\0\0\0\0\0\0", 8) + raw<uint64_t>(0) + std::string(64, '\0') +
                           values_;
        std::vector<std::tuple<std::string, uint64_t, uint64_t>> sections;
        auto section = [&](const std::string& name, const std::string& bytes) {
            sections.emplace_back(name, file.size(), bytes.size());
            file += bytes;
        };
        const std::string tokensBlock = lz4(tokenChars);
        section("TOKENS", raw<uint64_t>(tokens_.size()) + raw<uint64_t>(tokenChars.size()) +
                              raw<uint64_t>(tokensBlock.size()) + tokensBlock);
        std::string stringTokens = raw<uint64_t>(strings_.size());
        for (uint32_t t : strings_) stringTokens += raw(t);
        section("STRINGS", stringTokens);
        const std::string repsBlock = lz4(reps);
        section("FIELDS", raw<uint64_t>(fieldTokens.size()) + integers(fieldTokens) + raw<uint64_t>(repsBlock.size()) +
                              repsBlock);
        section("FIELDSETS", raw<uint64_t>(fieldSets.size()) + integers(fieldSets));
        section("PATHS", raw<uint64_t>(pathIndexes.size()) + raw<uint64_t>(pathIndexes.size()) + integers(pathIndexes) +
                             integers(elements) + integers(jumps));
        section("SPECS", raw<uint64_t>(specPaths.size()) + integers(specPaths) + integers(specSets) + integers(specTypes));
        const uint64_t toc = file.size();
        file += raw<uint64_t>(sections.size());
        for (const auto& [name, start, size] : sections) {
            std::string padded = name;
            padded.resize(16, '\0');
            file += padded + raw(start) + raw(size);
        }
        std::memcpy(file.data() + 16, &toc, 8);
        return file;
    }

    template <class T>
    static std::string raw(T value) {
        return std::string(reinterpret_cast<const char*>(&value), sizeof(T));
    }

private:
    // TfFastCompression's single-chunk form: a zero chunk count, then one LZ4 block.
    static std::string lz4(const std::string& bytes) {
        std::string block(size_t(LZ4_compressBound(int(bytes.size()))), '\0');
        const int size = LZ4_compress_default(bytes.data(), block.data(), int(bytes.size()), int(block.size()));
        return std::string(1, '\0') + block.substr(0, size_t(size));
    }
    // A compressed integer array: its byte count, then (LZ4) a common value, 2-bit codes, the values.
    static std::string integers(const std::vector<uint32_t>& values) {
        std::string coded = raw<int32_t>(0) + std::string((values.size() * 2 + 7) / 8, '\xff');
        uint32_t previous = 0;
        for (uint32_t v : values) {
            coded += raw<uint32_t>(v - previous);
            previous = v;
        }
        const std::string block = lz4(coded);
        return raw<uint64_t>(block.size()) + block;
    }

    std::vector<std::string> tokens_;
    std::vector<uint32_t> strings_;  // token indexes
    std::string values_;
};

}  // namespace obscura::usda::test
