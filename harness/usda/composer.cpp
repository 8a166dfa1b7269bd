#include "harness/usda/composer.h"

#include <algorithm>
#include <map>
#include <set>

#include "harness/usda/path_expression.h"
#include "harness/usda/sdf_path.h"
#include "harness/usda/variable_expression.h"

namespace obscura::usda {

namespace {

// Paths authored in a node's layer stack, carried into the stage's namespace.
ListOp<std::string> mapped(const ListOp<std::string>& op, const IndexNode& node) {
    return op.transformed([&](const std::string& path) { return mapToRoot(node, path); });
}

std::vector<std::string> composeMappedPaths(const std::vector<std::pair<const ListOp<std::string>*, const IndexNode*>>& ops) {
    std::vector<ListOp<std::string>> owned;
    owned.reserve(ops.size());
    for (const auto& [op, node] : ops) owned.push_back(mapped(*op, *node));
    std::vector<const ListOp<std::string>*> pointers;
    for (const auto& op : owned) pointers.push_back(&op);
    return composeListOps(pointers);
}

// The strongest opinion for each key wins.
void mergeMetadata(std::map<std::string, Value>& into, const std::map<std::string, Value>& weaker) {
    for (const auto& [key, value] : weaker) into.emplace(key, value);
}

// A property spec with the node whose namespace its paths are in and its layer's time offset.
template <class Spec>
struct SpecOpinion {
    const Spec* spec;
    const IndexNode* node;
    LayerOffset time;
};

template <class Spec>
using SpecsByName = std::map<std::string, std::vector<SpecOpinion<Spec>>>;

// Time samples of a layer at the stage's times (Sdf's layer offsets applied, as UsdAttribute
// resolves them).
std::map<double, Value> samplesAtStageTimes(const std::map<double, Value>& samples, const LayerOffset& time) {
    if (time.isIdentity()) return samples;
    std::map<double, Value> out;
    for (const auto& [t, value] : samples) out.emplace_hint(out.end(), time.apply(t), value);
    return out;
}

// A path expression authored in `node`'s layer stack with its absolute paths in the indexed
// prim's namespace, as value resolution maps path expressions through arcs (relative patterns are
// anchored where they are used and need no mapping). Each absolute pattern's literal prefix (up to
// a `//` or an element with a wildcard) is mapped; braces (predicate arguments) and quotes are
// left alone.
std::string mappedPathExpression(const std::string& text, const IndexNode& node) {
    if (node.toRoot.empty()) return text;
    std::string out;
    int braces = 0;
    char quote = 0;
    for (size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (quote) {
            quote = c == quote ? 0 : quote;
        } else if (c == '"' || c == '\'') {
            quote = c;
        } else if (c == '{' || c == '}') {
            braces += c == '{' ? 1 : -1;
        } else if (c == '/' && braces == 0 && (i == 0 || std::string_view(" \t\n(+&-~%").find(text[i - 1]) != std::string_view::npos)) {
            size_t end = i;
            // A path ends where an operator, a parenthesis, a predicate or a collection name begins
            // (USD's prim names hold none of these characters).
            while (end < text.size() && std::string_view(" \t\n()+&-~{:").find(text[end]) == std::string_view::npos) ++end;
            // The literal prefix: elements before an empty one (`//`) or one with a wildcard.
            size_t literal = i + 1;
            for (size_t element = i + 1; element < end;) {
                const size_t next = std::min(text.find('/', element), end);
                if (next == element || text.find_first_of("*?[", element) < next) break;
                literal = next;
                element = next + 1;
            }
            if (literal > i + 1) {
                out += mapToRoot(node, text.substr(i, literal - i));
                i = literal;
                continue;
            }
        }
        out += c;
        ++i;
    }
    return out;
}

// The path expression of opinion `at` with each `%_` (the weaker expression) replaced by the next
// weaker opinion's, itself composed (SdfPathExpression::ComposeOver, as value resolution applies
// it); where no weaker opinion has one, `%_` stays and matches nothing.
std::string composedPathExpression(const std::vector<SpecOpinion<AttributeSpec>>& specs, size_t at) {
    std::string text = specs[at].spec->defaultValue->strings.empty()
                           ? ""
                           : mappedPathExpression(specs[at].spec->defaultValue->strings[0], *specs[at].node);
    if (text.find("%_") == std::string::npos) return text;
    for (size_t weaker = at + 1; weaker < specs.size(); ++weaker) {
        const std::optional<Value>& value = specs[weaker].spec->defaultValue;
        if (!value) continue;
        if (value->blocked) return text;
        const std::string replacement = "(" + composedPathExpression(specs, weaker) + ")";
        for (size_t found = text.find("%_"); found != std::string::npos; found = text.find("%_", found + replacement.size()))
            text.replace(found, 2, replacement);
        return text;
    }
    return text;
}

Attribute composeAttribute(const std::string& name, const std::vector<SpecOpinion<AttributeSpec>>& specs) {
    const AttributeSpec& strongest = *specs.front().spec;
    Attribute attr;
    attr.name = name;
    attr.typeName = strongest.typeName;
    attr.isUniform = strongest.isUniform;
    attr.isCustom = strongest.isCustom;
    attr.where = strongest.where;
    // Value resolution (UsdResolveInfo): at a time, the strongest opinion with a value gives it,
    // its time samples before its spline before its default (OpenUSD's spline proposal: "if both
    // are present on the same attribute, time samples will take precedence"), so time samples and
    // splines weaker than a default are not kept; the default (what UsdTimeCode::Default() reads)
    // is the strongest one. A default of None blocks every weaker opinion; one of AnimationBlock
    // only the weaker time samples and splines, so that a weaker default shows through, while
    // those of its own layer still win (testUsdAttributeBlocking).
    bool animationBlocked = false, samplesSettled = false, defaultSettled = false;
    for (size_t k = 0; k < specs.size(); ++k) {
        const auto& [spec, node, time] = specs[k];
        if (!samplesSettled && !animationBlocked && spec->timeSamples) {
            attr.timeSamples = samplesAtStageTimes(*spec->timeSamples, time);
            samplesSettled = true;
        }
        if (!samplesSettled && !animationBlocked && spec->spline) {
            attr.spline = time.isIdentity() ? spec->spline
                                            : std::make_shared<const Spline>(spec->spline->retimed(time.offset, time.scale));
            samplesSettled = true;
        }
        if (!defaultSettled && spec->defaultValue) {
            if (!spec->defaultValue->blocked) attr.defaultValue = *spec->defaultValue;
            if (attr.defaultValue && spec->type && spec->type->name == "pathExpression" && !attr.defaultValue->strings.empty())
                attr.defaultValue->strings.edit()[0] = composedPathExpression(specs, k);
            defaultSettled = samplesSettled = true;
        }
        animationBlocked = animationBlocked || spec->animationBlock;
        if (samplesSettled && defaultSettled) break;
    }
    std::vector<std::pair<const ListOp<std::string>*, const IndexNode*>> connections;
    for (const auto& [spec, node, time] : specs) {
        connections.emplace_back(&spec->connections, node);
        mergeMetadata(attr.metadata, spec->metadata);
    }
    const std::vector<std::string> sources = composeMappedPaths(connections);
    if (!sources.empty()) attr.connection = sources.front();
    return attr;
}

Relationship composeRelationship(const std::string& name, const std::vector<SpecOpinion<RelationshipSpec>>& specs) {
    std::vector<std::pair<const ListOp<std::string>*, const IndexNode*>> targets;
    std::map<std::string, Value> metadata;
    for (const auto& [spec, node, time] : specs) {
        targets.emplace_back(&spec->targets, node);
        mergeMetadata(metadata, spec->metadata);
    }
    return Relationship{name, composeMappedPaths(targets), specs.front().spec->where, std::move(metadata)};
}

void readStageMetadata(const Layer& layer, StageMetadata& out) {
    auto text = [&](const char* key) -> const std::string* {
        const auto it = layer.metadata.find(key);
        return it == layer.metadata.end() || it->second.strings.empty() ? nullptr : &it->second.strings.front();
    };
    auto number = [&](const char* key) -> std::optional<double> {
        const auto it = layer.metadata.find(key);
        if (it == layer.metadata.end() || it->second.numbers.empty()) return std::nullopt;
        return it->second.numbers.front();
    };
    if (const std::string* upAxis = text("upAxis")) out.upAxis = *upAxis;
    if (const std::string* defaultPrim = text("defaultPrim")) out.defaultPrim = *defaultPrim;
    if (const std::string* path = text("renderSettingsPrimPath")) out.renderSettingsPrimPath = *path;
    out.where = SourceLocation{layer.identifier, 0, 0};
    if (const std::string* doc = text("documentation")) out.doc = *doc;
    if (auto value = number("metersPerUnit")) out.metersPerUnit = *value;
    if (auto value = number("timeCodesPerSecond")) out.timeCodesPerSecond = *value;
    if (auto value = number("framesPerSecond")) out.framesPerSecond = *value;
    out.startTimeCode = number("startTimeCode");
    out.endTimeCode = number("endTimeCode");
}

// Child names from weakest to strongest opinion, as Pcp orders them: a referenced asset's
// children keep their order and local additions follow. Each carries its strongest spec's location.
template <class Range>
std::vector<Composer::ChildName> childNames(const Range& strongestFirstSpecs) {
    std::map<std::string, SourceLocation> strongest;
    for (const PrimSpec* spec : strongestFirstSpecs)
        for (const auto& child : spec->children) strongest.emplace(child->name, child->where);
    std::vector<Composer::ChildName> names;
    std::set<std::string> seen;
    for (auto it = strongestFirstSpecs.rbegin(); it != strongestFirstSpecs.rend(); ++it)
        for (const auto& child : (*it)->children)
            if (seen.insert(child->name).second) names.push_back({child->name, strongest.at(child->name)});
    return names;
}

}  // namespace

std::variant<std::unique_ptr<Stage>, Error> Composer::compose(std::string_view rootText, const std::string& identifier,
                                                              const StageOptions& options) {
    try {
        Composer composer(options);
        return composer.composeStage(composer.layers_.addRoot(rootText, identifier));
    } catch (CompositionFailure& failure) {
        return std::move(failure.error);
    }
}

std::unique_ptr<Stage> Composer::composeStage(const Layer& rootLayer) {
    rootStack_ = &layers_.stackOf(rootLayer);
    std::unique_ptr<Stage> stage(new Stage());
    readStageMetadata(rootLayer, stage->metadata_);
    // Not `= "/"`: assigning that literal trips a GCC 12 -Wrestrict false positive at -O2.
    stage->root_->path = std::string(1, '/');
    stage->primsByPath_["/"] = stage->root_.get();
    std::vector<const PrimSpec*> roots;
    for (const Layer* layer : rootStack_->layers) roots.push_back(&layer->pseudoRoot);
    IndexNode pseudoRoot;
    pseudoRoot.stack = rootStack_;
    pseudoRoot.site = std::string(1, '/');
    composeChildren(*stage, *stage->root_, pseudoRoot, childNames(roots));
    stage->warnings_ = diagnostics_.take();
    return stage;
}

void Composer::composeChildren(Stage& stage, Prim& parent, const IndexNode& parentIndex,
                               const std::vector<ChildName>& authored) {
    // A relocated prim leaves its source's place for its target's.
    const RelocatedChildren relocated = indexer_.relocatedChildren(parentIndex);
    std::vector<ChildName> children;
    for (const ChildName& child : authored)
        if (!relocated.movedAway.count(child.name)) children.push_back(child);
    for (const auto& target : relocated.movedIn)
        if (std::none_of(children.begin(), children.end(), [&](const ChildName& c) { return c.name == target.first; }))
            children.push_back({target.first, target.second});
    for (const ChildName& child : children) {
        const std::string path = sdfpath::appendChild(parent.path, child.name);
        const PrimIndexer::StagePrimIndex& staged = indexer_.stageIndex(*rootStack_, path, child.where);
        const IndexNode& index = *staged.index;
        const std::vector<Opinion> opinions = opinionsOf(index);
        if (opinions.empty()) continue;
        budget_.addPrim(path, child.where);
        std::unique_ptr<Prim> prim = composePrim(path, opinions, parent);
        prim->instancingKey = staged.instancingKey;
        budget_.holdPrim(*prim, child.where);
        std::vector<const PrimSpec*> specs;
        for (const Opinion& opinion : opinions) specs.push_back(opinion.spec);
        composeChildren(stage, *prim, index, childNames(specs));
        stage.primsByPath_[path] = prim.get();
        parent.children.push_back(std::move(prim));
    }
}

std::unique_ptr<Prim> Composer::composePrim(const std::string& path, const std::vector<Opinion>& opinions, Prim& parent) {
    auto prim = std::make_unique<Prim>();
    prim->name = sdfpath::nameOf(path);
    prim->path = path;
    prim->parent = &parent;
    prim->where = opinions.front().spec->where;
    // "over" only adds opinions: the strongest def or class decides what the prim is.
    prim->specifier = Specifier::Over;
    for (const Opinion& opinion : opinions) {
        if (opinion.spec->specifier == Specifier::Over) continue;
        prim->specifier = opinion.spec->specifier;
        break;
    }
    for (const Opinion& opinion : opinions) {
        if (opinion.spec->typeName.empty()) continue;
        prim->typeName = opinion.spec->typeName;
        break;
    }

    std::vector<const ListOp<std::string>*> apiSchemas;
    SpecsByName<AttributeSpec> attributes;
    SpecsByName<RelationshipSpec> relationships;
    for (const Opinion& opinion : opinions) {
        mergeMetadata(prim->metadata, opinion.spec->metadata);
        apiSchemas.push_back(&opinion.spec->apiSchemas);
        for (const auto& [name, spec] : opinion.spec->attributes)
            attributes[name].push_back({&spec, opinion.node, opinion.time});
        for (const auto& [name, spec] : opinion.spec->relationships)
            relationships[name].push_back({&spec, opinion.node, opinion.time});
    }
    prim->apiSchemas = composeListOps(apiSchemas);
    if (const auto it = prim->metadata.find("kind"); it != prim->metadata.end() && !it->second.strings.empty())
        prim->kind = it->second.strings.front();
    if (const auto it = prim->metadata.find("active"); it != prim->metadata.end() && !it->second.numbers.empty())
        prim->active = it->second.numbers.front() != 0.0;
    for (const auto& [name, specs] : attributes) {
        Attribute attribute = composeAttribute(name, specs);
        expandAssetExpressions(attribute);
        prim->attributes.emplace(name, std::move(attribute));
    }
    for (const auto& [name, specs] : relationships) prim->relationships.emplace(name, composeRelationship(name, specs));
    reportBadMembershipExpressions(*prim);
    return prim;
}

// Asset-valued attributes written as variable expressions hold what they evaluate to, over the
// root layer's expressionVariables (as UsdAttribute::Get evaluates them).
void Composer::expandAssetExpressions(Attribute& attribute) {
    if (attribute.typeName.find("asset") == std::string::npos) return;
    auto expand = [&](Value& value) {
        if (std::none_of(value.strings.begin(), value.strings.end(), isVariableExpression)) return;
        for (std::string& s : value.strings.edit()) s = layers_.expand(nullptr, s, attribute.where);
    };
    if (attribute.defaultValue) expand(*attribute.defaultValue);
    for (auto& [time, value] : attribute.timeSamples) expand(value);
}

// A collection's membershipExpression that does not parse makes it empty (as in USD): reported
// with where it is written.
void Composer::reportBadMembershipExpressions(const Prim& prim) {
    for (const auto& [name, attribute] : prim.attributes) {
        if (name.rfind("collection:", 0) != 0 || !name.ends_with(":membershipExpression")) continue;
        const std::optional<Value> value = attribute.evaluate(0.0);
        if (!value || value->strings.empty()) continue;
        auto parsed = PathExpression::parse(value->strings[0], prim.path);
        if (const auto* problem = std::get_if<std::string>(&parsed))
            diagnostics_.warn("membershipExpression:" + prim.path + "." + name, attribute.where,
                              prim.path + "." + name + ": " + *problem + "; the collection holds nothing");
    }
}

}  // namespace obscura::usda
