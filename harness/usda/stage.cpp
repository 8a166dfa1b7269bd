#include "harness/usda/stage.h"

#include <fstream>
#include <sstream>

#include "harness/usda/composer.h"

namespace obscura::usda {

std::string Error::str() const {
    if (where.line <= 0) return where.file + ": " + message;
    return where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": " + message;
}

size_t Value::size() const {
    if (!numbers.empty()) return numbers.size() / static_cast<size_t>(tupleSize > 0 ? tupleSize : 1);
    return strings.size();
}

const Attribute* Prim::attribute(const std::string& attrName) const {
    const auto it = attributes.find(attrName);
    return it == attributes.end() ? nullptr : &it->second;
}

const Relationship* Prim::relationship(const std::string& relName) const {
    const auto it = relationships.find(relName);
    return it == relationships.end() ? nullptr : &it->second;
}

Stage::Stage() : root_(std::make_unique<Prim>()) {}

std::variant<std::unique_ptr<Stage>, Error> Stage::open(const std::filesystem::path& file, const StageOptions& options) {
    std::ifstream in(file, std::ios::binary);
    std::error_code ec;
    if (!in || std::filesystem::is_directory(file, ec)) return Error{SourceLocation{file.string(), 0, 0}, "cannot open file"};
    std::ostringstream text;
    text << in.rdbuf();
    return Composer::compose(text.str(), file.string(), options);
}

std::variant<std::unique_ptr<Stage>, Error> Stage::openFromString(const std::string& text, const std::string& virtualPath,
                                                                    const StageOptions& options) {
    return Composer::compose(text, virtualPath, options);
}

const Prim* Stage::find(const std::string& path) const {
    const auto it = primsByPath_.find(path);
    return it == primsByPath_.end() ? nullptr : it->second;
}

std::vector<const Prim*> Stage::prims() const {
    // Like USD's default traversal: a prim that fails (undefined, inactive, abstract) prunes its subtree.
    std::vector<const Prim*> out;
    std::vector<const Prim*> pending;
    for (auto it = root_->children.rbegin(); it != root_->children.rend(); ++it) pending.push_back(it->get());
    while (!pending.empty()) {
        const Prim* prim = pending.back();
        pending.pop_back();
        if (prim->specifier != Specifier::Def || !prim->active) continue;
        out.push_back(prim);
        for (auto it = prim->children.rbegin(); it != prim->children.rend(); ++it) pending.push_back(it->get());
    }
    return out;
}

}  // namespace obscura::usda
