// Build-time tool: reads compiled shaders (SPIR-V) and writes the byte offset of every member of
// every struct and block they declare, as the compiler laid them out (std140, std430, push
// constants), into a C++ header. The C++ structs that mirror them check each member's offset
// against it with static_assert, so a member added, moved or resized on one side only fails the
// build.
//
//   generate_shader_layouts <out header> <shader.spv>...
//
// A struct that several shaders declare under one name must be laid out alike in all of them, since
// one CPU struct is uploaded for all; a difference is reported and fails the build. Blocks (uniform,
// storage and push-constant) are one shader's interface: they are written per shader, and once more
// under their own name when every shader declaring them agrees.
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// SPIR-V opcodes and decorations read here (SPIR-V specification, 3.32 and 3.20).
constexpr uint32_t kMagic = 0x07230203;
constexpr uint16_t kOpName = 5;
constexpr uint16_t kOpMemberName = 6;
constexpr uint16_t kOpDecorate = 71;
constexpr uint16_t kOpMemberDecorate = 72;
constexpr uint32_t kDecorationBlock = 2;
constexpr uint32_t kDecorationBufferBlock = 3;
constexpr uint32_t kDecorationOffset = 35;

struct Member {
    std::string name;
    int64_t offset = -1;
};

struct Struct {
    std::string name;
    bool block = false;                  // a uniform, storage or push-constant block
    std::map<uint32_t, Member> members;  // by index

    bool sameLayout(const Struct& other) const {
        if (members.size() != other.members.size()) return false;
        for (const auto& [index, m] : members) {
            auto it = other.members.find(index);
            if (it == other.members.end() || it->second.name != m.name || it->second.offset != m.offset) return false;
        }
        return true;
    }
};

std::string literalString(const std::vector<uint32_t>& words, size_t first, size_t end) {
    std::string s;
    for (size_t w = first; w < end; ++w)
        for (int b = 0; b < 4; ++b) {
            char c = char((words[w] >> (8 * b)) & 0xff);
            if (c == '\0') return s;
            s += c;
        }
    return s;
}

// The named structs of one module whose members carry Offset decorations.
std::vector<Struct> readStructs(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() < 20 || bytes.size() % 4) throw std::runtime_error(path + ": not a SPIR-V module");
    std::vector<uint32_t> words(bytes.size() / 4);
    std::memcpy(words.data(), bytes.data(), bytes.size());
    if (words[0] != kMagic) throw std::runtime_error(path + ": not a SPIR-V module (magic)");
    std::map<uint32_t, std::string> names;
    std::map<uint32_t, Struct> structs;
    for (size_t at = 5; at < words.size();) {
        const uint16_t op = uint16_t(words[at] & 0xffff), count = uint16_t(words[at] >> 16);
        if (count == 0 || at + count > words.size()) throw std::runtime_error(path + ": truncated instruction");
        if (op == kOpName) names[words[at + 1]] = literalString(words, at + 2, at + count);
        if (op == kOpMemberName) structs[words[at + 1]].members[words[at + 2]].name = literalString(words, at + 3, at + count);
        if (op == kOpDecorate && (words[at + 2] == kDecorationBlock || words[at + 2] == kDecorationBufferBlock))
            structs[words[at + 1]].block = true;
        if (op == kOpMemberDecorate && words[at + 3] == kDecorationOffset)
            structs[words[at + 1]].members[words[at + 2]].offset = words[at + 4];
        at += count;
    }
    std::vector<Struct> out;
    for (auto& [id, s] : structs) {
        bool laidOut = !s.members.empty();
        for (const auto& [index, m] : s.members) laidOut = laidOut && m.offset >= 0 && !m.name.empty();
        auto name = names.find(id);
        if (!laidOut || name == names.end() || name->second.empty()) continue;
        s.name = name->second;
        out.push_back(std::move(s));
    }
    return out;
}

std::string identifier(const std::string& s) {
    std::string out;
    for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return out;
}

std::string fileName(const std::string& path) {
    size_t slash = path.find_last_of('/');
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    if (name.size() > 4 && name.substr(name.size() - 4) == ".spv") name.resize(name.size() - 4);
    return name;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::cerr << "usage: generate_shader_layouts <out header> <shader.spv>...\n";
        return 2;
    }
    try {
        std::map<std::string, std::pair<std::string, Struct>> shared;  // struct name -> (first shader, layout)
        std::map<std::string, std::map<std::string, Struct>> blocks;   // shader -> block name -> layout
        int problems = 0;
        for (int i = 2; i < argc; ++i) {
            const std::string shader = fileName(argv[i]);
            std::map<std::string, Struct>& own = blocks[shader];
            for (const Struct& s : readStructs(argv[i])) {
                if (s.block) {
                    auto [same, fresh] = own.try_emplace(s.name, s);
                    if (!fresh && !same->second.sameLayout(s)) {
                        std::cerr << shader << ": block " << s.name << " has two layouts\n";
                        ++problems;
                    }
                    continue;
                }
                auto [seen, inserted] = shared.try_emplace(s.name, shader, s);
                if (!inserted && !seen->second.second.sameLayout(s)) {
                    std::cerr << shader << ": struct " << s.name << " is laid out unlike in " << seen->second.first << "\n";
                    ++problems;
                }
            }
        }
        // Blocks every shader that declares them lays out alike (a common header's) are named once too.
        std::map<std::string, std::optional<Struct>> agreed;
        for (const auto& [shader, own] : blocks)
            for (const auto& [name, s] : own) {
                auto [it, fresh] = agreed.try_emplace(name, s);
                if (!fresh && it->second && !it->second->sameLayout(s)) it->second.reset();
            }
        for (const auto& [name, s] : agreed)
            if (s && shared.count(name)) {
                std::cerr << "a block and a struct are both named " << name << "\n";
                ++problems;
            }
        auto write = [](std::ostringstream& out, const std::string& name, const Struct& s) {
            out << "struct " << identifier(name) << " {\n";
            for (const auto& [index, m] : s.members)
                out << "    static constexpr std::size_t " << identifier(m.name) << " = " << m.offset << ";\n";
            out << "};\n";
        };
        std::ostringstream header;
        header << "// Generated by cmake/generate_shader_layouts.cpp from the compiled shaders: the byte offset of\n"
                  "// every member of every struct and block, as the GLSL compiler laid it out. Do not edit.\n"
                  "#pragma once\n\n#include <cstddef>\n\n"
                  "// Member `member` of the C++ struct `cpp` sits where the shaders read member `member` of\n"
                  "// `glsl` (a name in obscura::shader_layout).\n"
                  "#define OBSCURA_SHADER_OFFSET(cpp, glsl, member) \\\n"
                  "    static_assert(offsetof(cpp, member) == ::obscura::shader_layout::glsl::member, \\\n"
                  "                  #cpp \".\" #member \" is not where the shaders read it\")\n\n"
                  "namespace obscura::shader_layout {\n\n"
                  "// Structs, and blocks, laid out alike in every shader that declares them.\n";
        for (const auto& [name, first] : shared) write(header, name, first.second);
        for (const auto& [name, s] : agreed)
            if (s) write(header, name, *s);
        for (const auto& [shader, own] : blocks) {
            if (own.empty()) continue;
            header << "\n// The blocks of " << shader << ".\nnamespace " << identifier(shader) << " {\n";
            for (const auto& [name, s] : own) write(header, name, s);
            header << "}  // namespace " << identifier(shader) << "\n";
        }
        header << "\n}  // namespace obscura::shader_layout\n";
        if (problems) return 1;
        // Rewritten only when it changed, so that what includes it is not rebuilt for nothing.
        std::ifstream previous(argv[1]);
        std::string old((std::istreambuf_iterator<char>(previous)), std::istreambuf_iterator<char>());
        if (old != header.str()) std::ofstream(argv[1]) << header.str();
    } catch (const std::exception& e) {
        std::cerr << e.what() << "\n";
        return 1;
    }
    return 0;
}
