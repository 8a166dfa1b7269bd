// SdfPathExpression, the language of UsdCollectionAPI's membershipExpression (OpenUSD, "Collections
// and Patterns"), for matching prims:
// - patterns: prim paths whose names may hold glob wildcards (`*`, `?`, `[abc]`, `[!a-z]`), `//`
//   for any run of descendants (`/World//Sphere*`; a trailing `//` adds every descendant; `//`
//   alone is everything), relative ones (`Child/*`, `../Sibling`) anchored at the collection's
//   prim, each name optionally qualified by a predicate in braces (`/Set/*{isa:Mesh}`; a lone
//   `{kind:component}` is `//*{kind:component}`);
// - predicates: abstract, defined, model, group (each with an optional bool), kind and isa (with
//   `strict`), specifier and hasAPI (with `instanceName`), combined by not, and, or and
//   parentheses; arguments as `{name:a,b}` or `{name(a, b, strict=true)}`;
// - operators, tightest first: `~` complement, implied union (white space), `+` union, `&`
//   intersection, `-` difference, left to right, and parentheses;
// - references to other collections' expressions: `%/Prim:name`, `%:name` (a collection of the
//   same prim); `%_` (the weaker opinion of this attribute) is replaced by it when the stage
//   composes (composer.cpp composedPathExpression); one left, where no weaker opinion resolves,
//   matches nothing, as in USD.
// A pattern naming a property (`/Prim.attr`) matches no prim. The `variant` predicate is refused
// at parse time (a composed prim does not keep its variant selections here).
#pragma once

#include "harness/usda/stage.h"

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace obscura::usda {

class PathExpression {
public:
    // The expression `text`, its relative patterns and %:name references anchored at the prim at
    // `anchor`; or what is wrong with it, naming the column (1-based).
    static std::variant<PathExpression, std::string> parse(std::string_view text, const std::string& anchor);

    // The expression of collection `name` on the prim at `primPath` (an expression reference's
    // target); nullopt where there is none, which matches nothing.
    using Lookup = std::function<std::optional<PathExpression>(const std::string& primPath, const std::string& name)>;
    // Whether `prim` is matched; `depth` counts the references followed, which stop at 16 (a
    // cycle of collections referring to each other matches nothing more).
    bool matches(const Prim& prim, const Lookup& lookup, int depth = 0) const;

    struct Predicate {
        enum class Op { Call, Not, And, Or } op = Op::Call;
        int left = -1, right = -1;  // operands (Not: left alone)
        std::string name;
        std::vector<std::string> arguments;
        std::map<std::string, std::string> named;
    };
    struct Component {
        bool anyDepthBefore = false;  // a `//` precedes it: any run of names, none included
        std::string glob;
        int predicate = -1;
    };
    struct Pattern {
        std::vector<Component> components;
        bool anyDepthAfter = false;  // a trailing `//`: the matched prims' descendants too
        bool property = false;       // names a property: matches no prim
    };
    struct Node {
        enum class Op { Pattern, Reference, Complement, ImpliedUnion, Union, Intersection, Difference } op;
        int left = -1, right = -1;
        size_t pattern = 0;
        std::string referencePrim, referenceName;  // referenceName "_": the weaker opinion
    };

private:
    friend class PathExpressionParser;
    bool matchNode(int node, const Prim& prim, const Lookup& lookup, int depth) const;
    bool matchPattern(const Pattern& pattern, const Prim& prim) const;
    bool matchComponents(const Pattern& pattern, size_t component, const std::vector<const Prim*>& chain,
                         size_t name) const;
    bool matchPredicate(int predicate, const Prim& prim) const;

    std::vector<Node> nodes_;
    std::vector<Pattern> patterns_;
    std::vector<Predicate> predicates_;
    int root_ = -1;
};

}  // namespace obscura::usda
