#include "harness/material_binding.h"

#include "harness/usda/path_expression.h"

namespace obscura::harness {
namespace {

const std::string kDirect = "material:binding";
const std::string kCollectionPrefix = "material:binding:collection:";
const std::string kCollectionPath = ".collection:";
constexpr int kMaxCollectionNesting = 16;  // deeper is a cycle of collections including each other

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// `ancestor` is `path` or one of its ancestors.
bool atOrAbove(const std::string& ancestor, const std::string& path) {
    if (ancestor == "/" || ancestor == path) return true;
    return path.size() > ancestor.size() && startsWith(path, ancestor) && path[ancestor.size()] == '/';
}

bool strongerThanDescendants(const usda::Relationship& binding) {
    const auto strength = binding.metadata.find("bindMaterialAs");
    return strength != binding.metadata.end() && !strength->second.strings.empty() &&
           strength->second.strings[0] == "strongerThanDescendants";
}

struct Binding {
    std::string material;
    const usda::Relationship* relationship;
};

// The binding `owner` holds for `purpose` ("" for all-purpose) that applies to the prim at
// `primPath`: its first collection binding (property order) whose collection holds the prim, else
// its direct binding.
std::optional<Binding> bindingOn(const usda::Stage& stage, const usda::Prim& owner, const std::string& purpose,
                                 const std::string& primPath) {
    const std::string prefix = kCollectionPrefix + (purpose.empty() ? "" : purpose + ":");
    for (auto it = owner.relationships.lower_bound(prefix);
         it != owner.relationships.end() && startsWith(it->first, prefix); ++it) {
        // All-purpose names have one token after the prefix, purpose-restricted ones two.
        if (it->first.find(':', prefix.size()) != std::string::npos) continue;
        const std::vector<std::string>& targets = it->second.targets;
        if (targets.size() != 2) continue;
        const bool firstIsCollection = targets[0].find(kCollectionPath) != std::string::npos;
        const std::string& collection = targets[firstIsCollection ? 0 : 1];
        const std::string& material = targets[firstIsCollection ? 1 : 0];
        if (collectionIncludes(stage, collection, primPath)) return Binding{material, &it->second};
    }
    const usda::Relationship* direct = owner.relationship(purpose.empty() ? kDirect : kDirect + ":" + purpose);
    if (direct && !direct->targets.empty()) return Binding{direct->targets.front(), direct};
    return std::nullopt;
}

// Rules 1 and 2: walking up from the prim, the first binding found, unless an ancestor's binding
// is stronger than its descendants'.
std::optional<std::string> boundFor(const usda::Stage& stage, const usda::Prim& prim, const std::string& purpose,
                                    bool ancestors) {
    std::optional<std::string> bound;
    for (const usda::Prim* p = &prim; p; p = ancestors ? p->parent : nullptr) {
        auto binding = bindingOn(stage, *p, purpose, prim.path);
        if (binding && (!bound || strongerThanDescendants(*binding->relationship))) bound = binding->material;
    }
    return bound;
}

// Rule 3: the purpose's own binding, else the all-purpose one.
std::optional<std::string> boundForPurpose(const usda::Stage& stage, const usda::Prim& prim, const std::string& purpose,
                                           bool ancestors) {
    if (auto bound = boundFor(stage, prim, purpose, ancestors)) return bound;
    return boundFor(stage, prim, "", ancestors);
}

std::string uniformToken(const usda::Prim& prim, const std::string& name, const char* fallback) {
    const usda::Attribute* a = prim.attribute(name);
    auto v = a ? a->evaluate(0.0) : std::nullopt;
    return v && !v->strings.empty() ? v->strings[0] : std::string(fallback);
}

// The membershipExpression of collection `name` on `owner`, parsed; nullopt where none is authored
// or it does not parse (the stage reported it when it opened).
std::optional<usda::PathExpression> membershipExpression(const usda::Prim& owner, const std::string& name) {
    const std::string expression = uniformToken(owner, "collection:" + name + ":membershipExpression", "");
    if (expression.empty()) return std::nullopt;
    auto parsed = usda::PathExpression::parse(expression, owner.path);
    if (auto* e = std::get_if<usda::PathExpression>(&parsed)) return std::move(*e);
    return std::nullopt;
}

bool includes(const usda::Stage& stage, const std::string& collectionPath, const std::string& primPath, int depth) {
    const size_t dot = collectionPath.find(kCollectionPath);
    if (dot == std::string::npos || depth > kMaxCollectionNesting) return false;
    const usda::Prim* owner = stage.find(collectionPath.substr(0, dot));
    if (!owner) return false;
    const std::string name = collectionPath.substr(dot + kCollectionPath.size());
    const std::string base = "collection:" + name + ":";
    const bool explicitOnly = uniformToken(*owner, base + "expansionRule", "expandPrims") == "explicitOnly";
    const usda::Attribute* includeRootAttribute = owner->attribute(base + "includeRoot");
    auto includeRootValue = includeRootAttribute ? includeRootAttribute->evaluate(0.0) : std::nullopt;
    const bool includeRoot = includeRootValue && !includeRootValue->numbers.empty() && includeRootValue->numbers[0] != 0;

    // The membership mode ("Collections and Patterns"): "automatic", the fallback, takes the
    // expression where no include, exclude or includeRoot says otherwise.
    auto hasTargets = [&](const char* list) {
        const usda::Relationship* r = owner->relationship(base + list);
        return r && !r->targets.empty();
    };
    const std::string mode = uniformToken(*owner, base + "mode", "automatic");
    if (mode == "expression" ||
        (mode == "automatic" && !hasTargets("includes") && !hasTargets("excludes") && !includeRoot)) {
        const std::optional<usda::PathExpression> expression = membershipExpression(*owner, name);
        const usda::Prim* prim = stage.find(primPath);
        auto lookup = [&](const std::string& path, const std::string& referenced) -> std::optional<usda::PathExpression> {
            const usda::Prim* other = stage.find(path);
            return other ? membershipExpression(*other, referenced) : std::nullopt;
        };
        return expression && prim && expression->matches(*prim, lookup);
    }

    // The most specific include or exclude path at or above the prim decides (an exclude wins a tie).
    std::optional<bool> decided;
    size_t decidingLength = 0;
    bool viaCollection = false;
    auto consider = [&](const char* list, bool include) {
        const usda::Relationship* paths = owner->relationship(base + list);
        if (!paths) return;
        for (const std::string& target : paths->targets) {
            if (target.find(kCollectionPath) != std::string::npos) {
                viaCollection = viaCollection || (include && includes(stage, target, primPath, depth + 1));
                continue;
            }
            const bool matches = explicitOnly ? target == primPath : atOrAbove(target, primPath);
            if (!matches || (decided && target.size() < decidingLength) ||
                (decided && target.size() == decidingLength && include))
                continue;
            decided = include;
            decidingLength = target.size();
        }
    };
    consider("includes", true);
    consider("excludes", false);
    if (decided) return *decided;
    return viaCollection || (includeRoot && !explicitOnly);
}

}  // namespace

bool collectionIncludes(const usda::Stage& stage, const std::string& collectionPath, const std::string& primPath) {
    return includes(stage, collectionPath, primPath, 0);
}

std::optional<std::string> resolveBoundMaterial(const usda::Stage& stage, const usda::Prim& prim,
                                                const DrawableMaterial& drawable, bool ancestors) {
    std::optional<std::string> full = boundForPurpose(stage, prim, "full", ancestors);
    if (full && drawable(*full)) return full;
    std::optional<std::string> preview = boundForPurpose(stage, prim, "preview", ancestors);
    if (preview && drawable(*preview)) return preview;
    return full;
}

}  // namespace obscura::harness
