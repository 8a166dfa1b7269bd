#include "harness/usda/crate_file.h"

#include <algorithm>
#include <array>

namespace obscura::usda::crate {

namespace {

constexpr uint32_t kFieldSetEnd = ~0u;  // ends each run of field indexes in FIELDSETS
constexpr size_t kBootstrapBytes = 88;  // ident[8], version[8], tocOffset, reserved[8]

}  // namespace

std::span<const char> ByteReader::take(uint64_t count) {
    if (position_ > bytes_.size() || count > bytes_.size() - position_)
        throw Failure{position_, "reading " + std::to_string(count) + " bytes runs past the end of the data (" +
                                     std::to_string(bytes_.size()) + " bytes)"};
    const auto out = bytes_.subspan(position_, count);
    position_ += count;
    return out;
}

std::string Version::str() const {
    return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

File::File(std::span<const char> bytes) : bytes_(bytes) {
    if (bytes.size() < kBootstrapBytes)
        throw Failure{0, "file of " + std::to_string(bytes.size()) + " bytes is too short for the crate header"};
    if (std::memcmp(bytes.data(), "PXR-USDC", 8) != 0) throw Failure{0, "missing the crate identifier 'PXR-USDC'"};
    ByteReader header(bytes, 8);
    const auto versionBytes = header.take(8);
    version_ = Version{static_cast<unsigned char>(versionBytes[0]), static_cast<unsigned char>(versionBytes[1]),
                       static_cast<unsigned char>(versionBytes[2])};
    if (!version_.atLeast(kOldestVersion.major, kOldestVersion.minor) || version_.major != kNewestVersion.major ||
        version_.minor > kNewestVersion.minor)
        throw Failure{8, "crate version " + version_.str() + " is not supported (reads " + kOldestVersion.str() + " to " +
                             kNewestVersion.str() + ")"};
    const uint64_t tocOffset = header.read<uint64_t>();
    if (tocOffset < kBootstrapBytes || tocOffset >= bytes.size())
        throw Failure{16, "table of contents at byte " + std::to_string(tocOffset) + " lies outside the file of " +
                              std::to_string(bytes.size()) + " bytes (truncated?)"};

    ByteReader toc(bytes, tocOffset);
    const uint64_t count = checkedCount(toc.read<uint64_t>(), 32, tocOffset);
    for (uint64_t i = 0; i < count; ++i) {
        const uint64_t at = toc.tell();
        const auto nameBytes = toc.take(16);
        const std::string name(nameBytes.data(), strnlen(nameBytes.data(), nameBytes.size()));
        Section section{toc.read<uint64_t>(), toc.read<uint64_t>()};
        if (section.start > bytes.size() || section.size > bytes.size() - section.start)
            throw Failure{at, "section " + name + " (bytes " + std::to_string(section.start) + " to " +
                                  std::to_string(section.start + section.size) + ") lies outside the file of " +
                                  std::to_string(bytes.size()) + " bytes"};
        sections_.emplace_back(name, section);
    }
    readTokens(section("TOKENS"));
    readStrings(section("STRINGS"));
    readFields(section("FIELDS"));
    readFieldSets(section("FIELDSETS"));
    readPaths(section("PATHS"));
    readSpecs(section("SPECS"));
}

File::Section File::section(const char* name) const {
    for (const auto& [sectionName, section] : sections_)
        if (sectionName == name) return section;
    throw Failure{0, std::string("the table of contents has no ") + name + " section"};
}

uint64_t File::checkedCount(uint64_t count, uint64_t bytesEach, uint64_t at) const {
    if (bytesEach > 0 && count > bytes_.size() / bytesEach)
        throw Failure{at, "count " + std::to_string(count) + " cannot fit in a file of " + std::to_string(bytes_.size()) +
                              " bytes"};
    return count;
}

template <class Int>
std::vector<Int> File::readCompressedIntegers(ByteReader& reader, uint64_t count) const {
    const uint64_t at = reader.tell();
    const uint64_t size = reader.read<uint64_t>();
    const auto compressed = reader.take(size);
    return decompressIntegers<Int>(compressed, count, at + 8);
}

void File::readTokens(Section section) {
    ByteReader reader(bytes_.first(section.start + section.size), section.start);
    const uint64_t count = reader.read<uint64_t>();
    const uint64_t uncompressedSize = reader.read<uint64_t>();
    const uint64_t compressedSize = reader.read<uint64_t>();
    const uint64_t at = reader.tell();
    const auto compressed = reader.take(compressedSize);
    if (uncompressedSize > compressedSize * 256 + 64)
        throw Failure{section.start + 8, "tokens claim " + std::to_string(uncompressedSize) + " bytes from " +
                                             std::to_string(compressedSize) + " compressed bytes"};
    const std::vector<char> chars = decompressLz4(compressed, uncompressedSize, at);
    if (count > chars.size()) throw Failure{section.start, "claims " + std::to_string(count) + " tokens in " +
                                                               std::to_string(chars.size()) + " bytes"};
    tokens_.reserve(count);
    size_t pos = 0;
    while (tokens_.size() < count && pos < chars.size()) {
        const auto end = std::find(chars.begin() + static_cast<ptrdiff_t>(pos), chars.end(), '\0');
        tokens_.emplace_back(chars.begin() + static_cast<ptrdiff_t>(pos), end);
        pos = static_cast<size_t>(end - chars.begin()) + 1;
    }
    if (tokens_.size() != count)
        throw Failure{section.start, "claims " + std::to_string(count) + " tokens, holds " + std::to_string(tokens_.size())};
}

void File::readStrings(Section section) {
    ByteReader reader(bytes_.first(section.start + section.size), section.start);
    const uint64_t count = checkedCount(reader.read<uint64_t>(), 4, section.start);
    strings_.resize(count);
    const auto data = reader.take(count * 4);
    if (count > 0) std::memcpy(strings_.data(), data.data(), data.size());
}

void File::readFields(Section section) {
    ByteReader reader(bytes_.first(section.start + section.size), section.start);
    const uint64_t count = reader.read<uint64_t>();
    const std::vector<uint32_t> tokens = readCompressedIntegers<uint32_t>(reader, count);
    const uint64_t at = reader.tell();
    const uint64_t repsSize = reader.read<uint64_t>();
    const auto compressed = reader.take(repsSize);
    const std::vector<char> reps = decompressLz4(compressed, count * 8, at + 8);
    if (reps.size() != count * 8)
        throw Failure{at, "field values decode to " + std::to_string(reps.size()) + " bytes, expected " +
                              std::to_string(count * 8)};
    fields_.resize(count);
    for (uint64_t i = 0; i < count; ++i) {
        if (tokens[i] >= tokens_.size())
            throw Failure{section.start, "field " + std::to_string(i) + " names token " + std::to_string(tokens[i]) +
                                             " of " + std::to_string(tokens_.size())};
        fields_[i].token = tokens[i];
        std::memcpy(&fields_[i].rep.bits, reps.data() + i * 8, 8);
    }
}

void File::readFieldSets(Section section) {
    ByteReader reader(bytes_.first(section.start + section.size), section.start);
    const uint64_t count = reader.read<uint64_t>();
    fieldSets_ = readCompressedIntegers<uint32_t>(reader, count);
    for (uint32_t index : fieldSets_)
        if (index != kFieldSetEnd && index >= fields_.size())
            throw Failure{section.start, "field set names field " + std::to_string(index) + " of " +
                                             std::to_string(fields_.size())};
    if (!fieldSets_.empty() && fieldSets_.back() != kFieldSetEnd)
        throw Failure{section.start, "field sets do not end with a terminator"};
}

void File::readPaths(Section section) {
    ByteReader reader(bytes_.first(section.start + section.size), section.start);
    const uint64_t total = reader.read<uint64_t>();
    const uint64_t encoded = reader.read<uint64_t>();
    // Every path but the empty one is encoded.
    if (encoded > total || total > encoded + 1)
        throw Failure{section.start, "path table of " + std::to_string(total) + " paths encodes " +
                                         std::to_string(encoded)};
    const auto pathIndexes = readCompressedIntegers<uint32_t>(reader, encoded);
    const auto elementTokens = readCompressedIntegers<int32_t>(reader, encoded);
    const auto jumps = readCompressedIntegers<int32_t>(reader, encoded);
    paths_.assign(total, PathNode{});
    std::vector<bool> seen(total);
    auto bad = [&](const std::string& what) { return Failure{section.start, "corrupt path table: " + what}; };

    // Depth-first over the encoded tree without recursion (a hostile file could nest deeply):
    // jumps[i] is -2 for a leaf, -1 for "a child follows", 0 for "a sibling follows", and a
    // positive offset to the sibling when a child follows too.
    std::vector<std::pair<uint64_t, int64_t>> pending{{0, -1}};
    while (!pending.empty() && encoded > 0) {
        auto [current, parent] = pending.back();
        pending.pop_back();
        for (;;) {
            if (current >= encoded) throw bad("entry " + std::to_string(current) + " of " + std::to_string(encoded));
            const uint32_t index = pathIndexes[current];
            if (index >= total || seen[index]) throw bad("path index " + std::to_string(index) + " repeated or too large");
            seen[index] = true;
            PathNode& node = paths_[index];
            if (parent < 0) {
                if (current != 0) throw bad("a second root");
                node.text = "/";
            } else {
                const int32_t element = elementTokens[current];
                const uint64_t tokenIndex = element < 0 ? uint64_t(0) - uint64_t(int64_t(element)) : uint64_t(element);
                if (tokenIndex >= tokens_.size()) throw bad("element token " + std::to_string(tokenIndex));
                const std::string& token = tokens_[tokenIndex];
                const PathNode& parentNode = paths_[static_cast<size_t>(parent)];
                node.parent = parent;
                node.depth = parentNode.depth + 1;
                if (node.depth > kMaxPathDepth)
                    throw bad("paths nested deeper than " + std::to_string(kMaxPathDepth) + " levels");
                if (element < 0) {
                    node.kind = PathNode::Kind::Property;
                    node.name = token;
                    node.text = parentNode.text + "." + token;
                } else if (!token.empty() && token.front() == '{') {
                    const size_t eq = token.find('=');
                    if (eq == std::string::npos || token.back() != '}') throw bad("variant element '" + token + "'");
                    node.kind = PathNode::Kind::Variant;
                    node.name = token.substr(1, eq - 1);
                    node.variant = token.substr(eq + 1, token.size() - eq - 2);
                    node.text = parentNode.text + token;
                } else {
                    node.kind = PathNode::Kind::Prim;
                    node.name = token;
                    node.text = (parentNode.text == "/" ? "" : parentNode.text) + "/" + token;
                }
            }
            const int32_t jump = jumps[current];
            const bool hasChild = jump > 0 || jump == -1;
            const bool hasSibling = jump >= 0;
            if (hasChild && hasSibling) pending.emplace_back(current + static_cast<uint64_t>(jump), parent);
            if (hasChild) parent = index;
            if (!hasChild && !hasSibling) break;
            ++current;
        }
    }
}

void File::readSpecs(Section section) {
    ByteReader reader(bytes_.first(section.start + section.size), section.start);
    const uint64_t count = reader.read<uint64_t>();
    const auto paths = readCompressedIntegers<uint32_t>(reader, count);
    const auto fieldSets = readCompressedIntegers<uint32_t>(reader, count);
    const auto types = readCompressedIntegers<uint32_t>(reader, count);
    specs_.resize(count);
    for (uint64_t i = 0; i < count; ++i) {
        const std::string which = "spec " + std::to_string(i);
        if (paths[i] >= paths_.size() || (paths_[paths[i]].text.empty()))
            throw Failure{section.start, which + " names path " + std::to_string(paths[i]) + ", which is not in the table"};
        if (fieldSets[i] >= fieldSets_.size() || (fieldSets[i] > 0 && fieldSets_[fieldSets[i] - 1] != kFieldSetEnd))
            throw Failure{section.start, which + " names field set " + std::to_string(fieldSets[i]) + ", which does not start one"};
        if (types[i] == 0 || types[i] > static_cast<uint32_t>(SpecType::VariantSet))
            throw Failure{section.start, which + " has unknown spec type " + std::to_string(types[i])};
        specs_[i] = Spec{paths[i], fieldSets[i], static_cast<SpecType>(types[i])};
    }
}

const std::string& File::token(uint64_t index, uint64_t at) const {
    if (index >= tokens_.size())
        throw Failure{at, "token index " + std::to_string(index) + " of " + std::to_string(tokens_.size())};
    return tokens_[index];
}

const std::string& File::string(uint64_t index, uint64_t at) const {
    if (index >= strings_.size())
        throw Failure{at, "string index " + std::to_string(index) + " of " + std::to_string(strings_.size())};
    return token(strings_[index], at);
}

const PathNode& File::path(uint64_t index, uint64_t at) const {
    if (index >= paths_.size() || paths_[index].text.empty())
        throw Failure{at, "path index " + std::to_string(index) + " of " + std::to_string(paths_.size())};
    return paths_[index];
}

const std::string& File::pathText(uint64_t index, uint64_t at) const {
    if (index < paths_.size() && paths_[index].text.empty()) return paths_[index].text;
    return path(index, at).text;
}

}  // namespace obscura::usda::crate
