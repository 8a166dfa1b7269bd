#include "harness/usda/path_expression.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace obscura::usda {

namespace {

constexpr int kMaxReferenceDepth = 16;
// Bounds on what one expression may build, so that no text exhausts the stack of the recursive
// parsing and matching: nesting of parentheses, complements and `not`s, and nodes in all.
constexpr int kMaxNesting = 64;
constexpr size_t kMaxNodes = 4096;

// Operator binding powers, tightest first (SdfPathExpression::Op's order).
constexpr int kImpliedUnionPower = 40, kUnionPower = 30, kIntersectionPower = 20, kDifferencePower = 10;

// The typed schemas a prim type derives from, as UsdSchemaRegistry knows them (the predicate
// isa's "or subtypes"): each type's base.
const std::map<std::string, std::string> kSchemaBases = {
    {"Imageable", "Typed"},
    {"Scope", "Imageable"},
    {"Xformable", "Imageable"},
    {"Xform", "Xformable"},
    {"Camera", "Xformable"},
    {"Boundable", "Xformable"},
    {"Gprim", "Boundable"},
    {"PointBased", "Gprim"},
    {"Mesh", "PointBased"},
    {"Points", "PointBased"},
    {"NurbsPatch", "PointBased"},
    {"TetMesh", "PointBased"},
    {"Curves", "PointBased"},
    {"BasisCurves", "Curves"},
    {"NurbsCurves", "Curves"},
    {"HermiteCurves", "Curves"},
    {"Sphere", "Gprim"},
    {"Cube", "Gprim"},
    {"Cylinder", "Gprim"},
    {"Cylinder_1", "Gprim"},
    {"Cone", "Gprim"},
    {"Capsule", "Gprim"},
    {"Capsule_1", "Gprim"},
    {"Plane", "Gprim"},
    {"Volume", "Gprim"},
    {"PointInstancer", "Boundable"},
    {"GeomSubset", "Typed"},
    {"BoundableLightBase", "Boundable"},
    {"NonboundableLightBase", "Xformable"},
    {"SphereLight", "BoundableLightBase"},
    {"RectLight", "BoundableLightBase"},
    {"DiskLight", "BoundableLightBase"},
    {"CylinderLight", "BoundableLightBase"},
    {"PortalLight", "BoundableLightBase"},
    {"DistantLight", "NonboundableLightBase"},
    {"DomeLight", "NonboundableLightBase"},
    {"DomeLight_1", "NonboundableLightBase"},
    {"GeometryLight", "NonboundableLightBase"},
    {"PluginLight", "Xformable"},
    {"LightFilter", "Xformable"},
    {"Shader", "Typed"},
    {"NodeGraph", "Typed"},
    {"Material", "NodeGraph"},
    {"SkelRoot", "Boundable"},
    {"Skeleton", "Boundable"},
    {"SkelAnimation", "Typed"},
    {"BlendShape", "Typed"},
    {"RenderSettingsBase", "Typed"},
    {"RenderSettings", "RenderSettingsBase"},
    {"RenderProduct", "RenderSettingsBase"},
    {"RenderVar", "Typed"},
    {"RenderPass", "Typed"},
};

// A schema named by its class ("UsdGeomMesh") or its type name ("Mesh").
std::string schemaTypeName(const std::string& name) {
    for (const char* prefix : {"UsdGeom", "UsdLux", "UsdShade", "UsdSkel", "UsdVol", "UsdRender", "UsdMedia", "Usd"})
        if (name.rfind(prefix, 0) == 0 && name.size() > std::string_view(prefix).size() &&
            std::isupper(static_cast<unsigned char>(name[std::string_view(prefix).size()])))
            return name.substr(std::string_view(prefix).size());
    return name;
}

bool isA(const std::string& type, const std::string& schema, bool strict) {
    if (strict) return type == schema;
    for (std::string t = type; !t.empty();) {
        if (t == schema) return true;
        const auto base = kSchemaBases.find(t);
        t = base == kSchemaBases.end() ? std::string() : base->second;
    }
    return false;
}

// UsdModelAPI's kinds: model (with its subkinds component, group and its subkind assembly) and
// subcomponent.
bool isKindOf(const std::string& kind, const std::string& base, bool strict) {
    if (kind == base) return true;
    if (strict) return false;
    if (base == "model") return kind == "component" || kind == "group" || kind == "assembly";
    return base == "group" && kind == "assembly";
}

bool isRootChild(const Prim& prim) { return !prim.parent || !prim.parent->parent; }

// UsdPrim::IsGroup and IsModel: a kind of the family on a prim whose ancestors are all groups.
bool isGroup(const Prim& prim) {
    return isKindOf(prim.kind, "group", false) && (isRootChild(prim) || isGroup(*prim.parent));
}
bool isModel(const Prim& prim) {
    return isKindOf(prim.kind, "model", false) && (isRootChild(prim) || isGroup(*prim.parent));
}

bool globMatches(std::string_view glob, std::string_view name) {
    if (glob.empty()) return name.empty();
    if (glob[0] == '*') {
        while (glob.size() > 1 && glob[1] == '*') glob.remove_prefix(1);
        for (size_t skip = 0; skip <= name.size(); ++skip)
            if (globMatches(glob.substr(1), name.substr(skip))) return true;
        return false;
    }
    if (name.empty()) return false;
    const size_t close = glob[0] == '[' ? glob.find(']', 1) : std::string_view::npos;
    if (close != std::string_view::npos) {
        std::string_view set = glob.substr(1, close - 1);
        const bool negated = !set.empty() && (set[0] == '!' || set[0] == '^');
        if (negated) set.remove_prefix(1);
        bool in = false;
        for (size_t i = 0; i < set.size(); ++i) {
            if (i + 2 < set.size() && set[i + 1] == '-') {
                in = in || (name[0] >= set[i] && name[0] <= set[i + 2]);
                i += 2;
            } else {
                in = in || name[0] == set[i];
            }
        }
        return in != negated && globMatches(glob.substr(close + 1), name.substr(1));
    }
    return (glob[0] == '?' || glob[0] == name[0]) && globMatches(glob.substr(1), name.substr(1));
}

bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

bool flag(const std::string& value) { return value != "false" && value != "0"; }

}  // namespace

class PathExpressionParser {
public:
    PathExpressionParser(std::string_view text, const std::string& anchor) : text_(text), anchor_(anchor) {}

    std::variant<PathExpression, std::string> parse() {
        skipBlanks();
        if (pos_ == text_.size()) {
            // The empty expression matches nothing.
            out_.nodes_.push_back({PathExpression::Node::Op::Complement, add(everything()), -1});
            out_.root_ = int(out_.nodes_.size()) - 1;
            return std::move(out_);
        }
        out_.root_ = expression(0);
        skipBlanks();
        if (error_.empty() && pos_ != text_.size()) fail("unexpected '" + std::string(1, text_[pos_]) + "'");
        if (!error_.empty()) return error_;
        return std::move(out_);
    }

private:
    using Node = PathExpression::Node;
    using Predicate = PathExpression::Predicate;

    void fail(const std::string& what) {
        if (error_.empty()) error_ = "column " + std::to_string(pos_ + 1) + ": " + what;
        pos_ = text_.size();
    }
    bool skipBlanks() {
        const size_t start = pos_;
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
        return pos_ > start;
    }
    bool at(char c) const { return pos_ < text_.size() && text_[pos_] == c; }
    int add(Node node) {
        if (out_.nodes_.size() >= kMaxNodes) fail("more than " + std::to_string(kMaxNodes) + " terms");
        out_.nodes_.push_back(std::move(node));
        return int(out_.nodes_.size()) - 1;
    }
    Node everything() {
        PathExpression::Pattern all;
        all.anyDepthAfter = true;
        out_.patterns_.push_back(std::move(all));
        Node node{Node::Op::Pattern};
        node.pattern = out_.patterns_.size() - 1;
        return node;
    }

    // Pratt parsing: operators bind left to right, tighter ones first.
    int expression(int minPower) {
        int left = factor();
        while (error_.empty()) {
            const size_t before = pos_;
            const bool blanks = skipBlanks();
            if (pos_ == text_.size() || at(')')) {
                pos_ = before;
                break;
            }
            Node::Op op = Node::Op::ImpliedUnion;
            int power = kImpliedUnionPower;
            if (at('+')) op = Node::Op::Union, power = kUnionPower;
            else if (at('&')) op = Node::Op::Intersection, power = kIntersectionPower;
            else if (at('-')) op = Node::Op::Difference, power = kDifferencePower;
            else if (!blanks) {
                fail("expected an operator");
                break;
            }
            if (power < minPower) {
                pos_ = before;
                break;
            }
            if (op != Node::Op::ImpliedUnion) ++pos_;
            const int right = expression(power + 1);
            left = add({op, left, right});
        }
        return left;
    }

    // One level of nesting for the duration of a scope.
    struct Nested {
        PathExpressionParser& parser;
        explicit Nested(PathExpressionParser& p) : parser(p) {
            if (++parser.nesting_ > kMaxNesting) parser.fail("nested more than " + std::to_string(kMaxNesting) + " deep");
        }
        ~Nested() { --parser.nesting_; }
    };

    int factor() {
        Nested nested(*this);
        if (!error_.empty()) return -1;
        skipBlanks();
        if (pos_ == text_.size()) {
            fail("expected a pattern");
            return -1;
        }
        if (at('~')) {
            ++pos_;
            return add({Node::Op::Complement, factor(), -1});
        }
        if (at('(')) {
            ++pos_;
            const int inner = expression(0);
            skipBlanks();
            if (!at(')')) fail("expected ')'");
            else ++pos_;
            return inner;
        }
        if (at('%')) return reference();
        return pattern();
    }

    // `%/Prim:name`, `%:name` (the anchor's), `%_` (the weaker opinion).
    int reference() {
        ++pos_;
        Node node{Node::Op::Reference};
        if (at('_') && (pos_ + 1 == text_.size() || !isNameChar(text_[pos_ + 1]))) {
            ++pos_;
            node.referenceName = "_";
            return add(std::move(node));
        }
        const size_t start = pos_;
        while (pos_ < text_.size() && (isNameChar(text_[pos_]) || text_[pos_] == '/' || text_[pos_] == '.')) ++pos_;
        const std::string path(text_.substr(start, pos_ - start));
        if (!at(':')) {
            fail("expected ':' and a collection name in an expression reference");
            return -1;
        }
        ++pos_;
        const size_t nameStart = pos_;
        while (pos_ < text_.size() && (isNameChar(text_[pos_]) || text_[pos_] == ':')) ++pos_;
        node.referenceName = std::string(text_.substr(nameStart, pos_ - nameStart));
        if (node.referenceName.empty()) fail("expected a collection name in an expression reference");
        std::vector<std::string> names;
        if (!absolutePrimPath(path.empty() ? "." : path, names)) return -1;
        for (const std::string& n : names) node.referencePrim += "/" + n;
        if (node.referencePrim.empty()) node.referencePrim = "/";
        return add(std::move(node));
    }

    // The prim names of `path`, relative ones (`.`, `..`, `Child`) resolved against the anchor.
    bool absolutePrimPath(const std::string& path, std::vector<std::string>& names) {
        if (path.empty() || path[0] != '/') names = anchorNames();
        size_t start = 0;
        while (start <= path.size()) {
            const size_t slash = std::min(path.find('/', start), path.size());
            const std::string name = path.substr(start, slash - start);
            if (name == "..") {
                if (names.empty()) {
                    fail("'..' above the root");
                    return false;
                }
                names.pop_back();
            } else if (!name.empty() && name != ".") {
                names.push_back(name);
            }
            start = slash + 1;
        }
        return true;
    }
    std::vector<std::string> anchorNames() const {
        std::vector<std::string> names;
        size_t start = 1;
        while (start < anchor_.size()) {
            const size_t slash = std::min(anchor_.find('/', start), anchor_.size());
            names.push_back(anchor_.substr(start, slash - start));
            start = slash + 1;
        }
        return names;
    }

    // The pattern's text: up to white space or an operator outside braces and brackets.
    std::string patternText() {
        const size_t start = pos_;
        int braces = 0;
        bool bracket = false;
        size_t opened = 0;
        for (; pos_ < text_.size(); ++pos_) {
            const char c = text_[pos_];
            if (bracket) bracket = c != ']';
            else if (c == '[' && braces == 0) bracket = true, opened = pos_;
            else if (c == '{' && braces++ == 0) opened = pos_;
            else if (c == '}') --braces;
            else if (braces == 0 && (std::isspace(static_cast<unsigned char>(c)) || c == '+' || c == '&' ||
                                     c == '-' || c == '(' || c == ')' || c == '~' || c == '%'))
                break;
        }
        if (braces != 0 || bracket) {
            pos_ = opened;
            fail("unclosed '{' or '['");
        }
        return std::string(text_.substr(start, pos_ - start));
    }

    int pattern() {
        const size_t start = pos_;
        std::string t = patternText();
        if (t.empty()) {
            fail("expected a pattern");
            return -1;
        }
        size_t column = start;  // of t[0] in the text
        if (t[0] == '{') t = "//*" + t, column -= 3;  // a lone predicate qualifies every prim
        // Split at '/' outside braces and brackets; empty pieces are the `//`s.
        std::vector<std::pair<std::string, size_t>> pieces;  // text, column
        size_t pieceStart = 0;
        int braces = 0;
        for (size_t i = 0; i <= t.size(); ++i) {
            if (i < t.size() && t[i] == '{') ++braces;
            if (i < t.size() && t[i] == '}') --braces;
            if (i == t.size() || (t[i] == '/' && braces == 0)) {
                pieces.emplace_back(t.substr(pieceStart, i - pieceStart), column + pieceStart);
                pieceStart = i + 1;
            }
        }
        PathExpression::Pattern p;
        const bool absolute = t[0] == '/';
        if (!absolute)
            for (const std::string& name : anchorNames()) p.components.push_back({false, name, -1});
        bool anyDepth = false;
        for (size_t i = absolute ? 1 : 0; i < pieces.size() && error_.empty(); ++i) {
            std::string piece = pieces[i].first;
            if (piece.empty()) {
                anyDepth = true;
                continue;
            }
            if (piece == "..") {
                if (p.components.empty() || anyDepth) fail("'..' above the root or after '//'");
                else p.components.pop_back();
                continue;
            }
            if (piece == ".") continue;
            PathExpression::Component c;
            c.anyDepthBefore = anyDepth;
            anyDepth = false;
            const size_t brace = piece.find('{');
            if (brace != std::string::npos) {
                if (piece.back() != '}') {
                    pos_ = pieces[i].second + brace;
                    fail("text after a predicate");
                    break;
                }
                c.predicate = predicate(piece.substr(brace + 1, piece.size() - brace - 2), pieces[i].second + brace + 1);
                piece.resize(brace);
            }
            if (piece.find('.') != std::string::npos) p.property = true;  // `/Prim.attr`: no prim
            c.glob = piece.empty() ? "*" : piece;
            p.components.push_back(std::move(c));
        }
        p.anyDepthAfter = anyDepth;
        out_.patterns_.push_back(std::move(p));
        Node node{Node::Op::Pattern};
        node.pattern = out_.patterns_.size() - 1;
        return add(std::move(node));
    }

    // Predicate expressions: not, and, or, parentheses and calls, within one pair of braces.
    int predicate(const std::string& text, size_t column) {
        PredicateParser parser{text, 0, this, column};
        const int root = parser.orExpression();
        parser.blanks();
        if (error_.empty() && parser.pos != text.size()) parser.fail("unexpected text in a predicate");
        return root;
    }

    struct PredicateParser {
        const std::string& text;
        size_t pos;
        PathExpressionParser* owner;
        size_t column;

        void fail(const std::string& what) {
            owner->pos_ = column + pos;
            owner->fail(what);
            pos = text.size();
        }
        void blanks() {
            while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
        }
        bool keyword(const char* word) {
            blanks();
            const size_t n = std::string_view(word).size();
            if (pos >= text.size() || text.compare(pos, n, word) != 0 || (pos + n < text.size() && isNameChar(text[pos + n]))) return false;
            pos += n;
            return true;
        }
        int add(Predicate p) {
            if (owner->out_.predicates_.size() >= kMaxNodes) fail("more than " + std::to_string(kMaxNodes) + " predicate terms");
            owner->out_.predicates_.push_back(std::move(p));
            return int(owner->out_.predicates_.size()) - 1;
        }
        int orExpression() {
            int left = andExpression();
            while (keyword("or")) left = add({Predicate::Op::Or, left, andExpression()});
            return left;
        }
        int andExpression() {
            int left = notExpression();
            while (keyword("and")) left = add({Predicate::Op::And, left, notExpression()});
            return left;
        }
        int notExpression() {
            struct Level {
                int& nesting;
                ~Level() { --nesting; }
            } level{++owner->nesting_};
            if (owner->nesting_ > kMaxNesting) fail("nested more than " + std::to_string(kMaxNesting) + " deep");
            if (!owner->error_.empty()) return -1;
            if (keyword("not")) return add({Predicate::Op::Not, notExpression(), -1});
            blanks();
            if (pos < text.size() && text[pos] == '(') {
                ++pos;
                const int inner = orExpression();
                blanks();
                if (pos >= text.size() || text[pos] != ')') fail("expected ')' in a predicate");
                else ++pos;
                return inner;
            }
            return call();
        }
        std::string word() {
            blanks();
            if (pos < text.size() && (text[pos] == '"' || text[pos] == '\'')) {
                const char quote = text[pos];
                const size_t close = text.find(quote, pos + 1);
                if (close == std::string::npos) {
                    fail("unclosed quote in a predicate");
                    return {};
                }
                std::string w = text.substr(pos + 1, close - pos - 1);
                pos = close + 1;
                return w;
            }
            const size_t start = pos;
            while (pos < text.size() && (isNameChar(text[pos]) || text[pos] == ':' || text[pos] == '.')) ++pos;
            return text.substr(start, pos - start);
        }
        int call() {
            Predicate p;
            blanks();
            const size_t start = pos;
            while (pos < text.size() && isNameChar(text[pos])) ++pos;
            p.name = text.substr(start, pos - start);
            static const std::set<std::string> known = {"abstract", "defined", "model", "group",
                                                        "kind",     "isa",     "specifier", "hasAPI"};
            if (p.name == "variant") {
                pos = start;
                fail("the 'variant' predicate is not supported");
                return -1;
            }
            if (!known.count(p.name)) {
                pos = start;
                fail("unknown predicate '" + p.name + "'");
                return -1;
            }
            if (pos < text.size() && text[pos] == ':') {
                // `name:a,b`: arguments without white space.
                do {
                    ++pos;
                    const size_t argStart = pos;
                    while (pos < text.size() && (isNameChar(text[pos]) || text[pos] == '.')) ++pos;
                    p.arguments.push_back(text.substr(argStart, pos - argStart));
                } while (pos < text.size() && text[pos] == ',');
            } else if (pos < text.size() && text[pos] == '(') {
                ++pos;
                blanks();
                while (pos < text.size() && text[pos] != ')') {
                    std::string value = word();
                    blanks();
                    if (pos < text.size() && text[pos] == '=') {
                        ++pos;
                        p.named[value] = word();
                        blanks();
                    } else {
                        p.arguments.push_back(value);
                    }
                    if (pos < text.size() && text[pos] == ',') ++pos;
                    else if (pos < text.size() && text[pos] != ')') fail("expected ',' or ')' in a predicate");
                    blanks();
                }
                if (pos >= text.size()) fail("expected ')' in a predicate");
                else ++pos;
            }
            return add(std::move(p));
        }
    };

    std::string_view text_;
    std::string anchor_;
    size_t pos_ = 0;
    std::string error_;
    int nesting_ = 0;
    PathExpression out_;
};

std::variant<PathExpression, std::string> PathExpression::parse(std::string_view text, const std::string& anchor) {
    return PathExpressionParser(text, anchor).parse();
}

bool PathExpression::matches(const Prim& prim, const Lookup& lookup, int depth) const {
    return root_ >= 0 && matchNode(root_, prim, lookup, depth);
}

bool PathExpression::matchNode(int index, const Prim& prim, const Lookup& lookup, int depth) const {
    const Node& node = nodes_[size_t(index)];
    switch (node.op) {
    case Node::Op::Pattern: return matchPattern(patterns_[node.pattern], prim);
    case Node::Op::Reference: {
        if (node.referenceName == "_" || depth >= kMaxReferenceDepth) return false;
        const std::optional<PathExpression> referenced = lookup(node.referencePrim, node.referenceName);
        return referenced && referenced->matches(prim, lookup, depth + 1);
    }
    case Node::Op::Complement: return !matchNode(node.left, prim, lookup, depth);
    case Node::Op::ImpliedUnion:
    case Node::Op::Union: return matchNode(node.left, prim, lookup, depth) || matchNode(node.right, prim, lookup, depth);
    case Node::Op::Intersection:
        return matchNode(node.left, prim, lookup, depth) && matchNode(node.right, prim, lookup, depth);
    case Node::Op::Difference:
        return matchNode(node.left, prim, lookup, depth) && !matchNode(node.right, prim, lookup, depth);
    }
    return false;
}

bool PathExpression::matchPattern(const Pattern& pattern, const Prim& prim) const {
    if (pattern.property || !prim.parent) return false;  // no prim is a property; the pseudo-root is no member
    std::vector<const Prim*> chain;
    for (const Prim* p = &prim; p && p->parent; p = p->parent) chain.push_back(p);
    std::reverse(chain.begin(), chain.end());
    return matchComponents(pattern, 0, chain, 0);
}

bool PathExpression::matchComponents(const Pattern& pattern, size_t component, const std::vector<const Prim*>& chain,
                                     size_t name) const {
    if (component == pattern.components.size())
        return name == chain.size() || (pattern.anyDepthAfter && name < chain.size());
    const Component& c = pattern.components[component];
    auto matchesHere = [&](size_t at) {
        return globMatches(c.glob, chain[at]->name) && (c.predicate < 0 || matchPredicate(c.predicate, *chain[at])) &&
               matchComponents(pattern, component + 1, chain, at + 1);
    };
    if (!c.anyDepthBefore) return name < chain.size() && matchesHere(name);
    for (size_t at = name; at < chain.size(); ++at)
        if (matchesHere(at)) return true;
    return false;
}

bool PathExpression::matchPredicate(int index, const Prim& prim) const {
    const Predicate& p = predicates_[size_t(index)];
    switch (p.op) {
    case Predicate::Op::Not: return !matchPredicate(p.left, prim);
    case Predicate::Op::And: return matchPredicate(p.left, prim) && matchPredicate(p.right, prim);
    case Predicate::Op::Or: return matchPredicate(p.left, prim) || matchPredicate(p.right, prim);
    case Predicate::Op::Call: break;
    }
    const bool wanted = p.arguments.empty() || flag(p.arguments[0]);
    const auto strictArgument = p.named.find("strict");
    const bool strict = strictArgument != p.named.end() && flag(strictArgument->second);
    auto any = [&](const std::function<bool(const std::string&)>& test) {
        return std::any_of(p.arguments.begin(), p.arguments.end(), test);
    };
    if (p.name == "abstract" || p.name == "defined") {
        bool abstract = false, defined = true;
        for (const Prim* a = &prim; a && a->parent; a = a->parent) {
            abstract = abstract || a->specifier == Specifier::Class;
            defined = defined && a->specifier != Specifier::Over;
        }
        return (p.name == "abstract" ? abstract : defined) == wanted;
    }
    if (p.name == "model") return isModel(prim) == wanted;
    if (p.name == "group") return isGroup(prim) == wanted;
    if (p.name == "kind") return any([&](const std::string& kind) { return isKindOf(prim.kind, kind, strict); });
    if (p.name == "isa")
        return any([&](const std::string& type) { return isA(prim.typeName, schemaTypeName(type), strict); });
    if (p.name == "specifier") {
        const char* own = prim.specifier == Specifier::Def ? "def" : prim.specifier == Specifier::Over ? "over" : "class";
        return any([&](const std::string& s) { return s == own; });
    }
    // hasAPI: a single-apply schema by name, a multiple-apply one by name and any (or the named) instance.
    const auto instance = p.named.find("instanceName");
    return any([&](const std::string& api) {
        const std::string name = schemaTypeName(api);
        return std::any_of(prim.apiSchemas.begin(), prim.apiSchemas.end(), [&](const std::string& applied) {
            const std::string appliedName = schemaTypeName(applied.substr(0, applied.find(':')));
            if (appliedName != name) return false;
            if (instance == p.named.end() || instance->second.empty()) return true;
            return applied.size() > applied.find(':') && applied.substr(applied.find(':') + 1) == instance->second;
        });
    });
}

}  // namespace obscura::usda
