#include "harness/usda/variable_expression.h"

#include <cctype>
#include <cstdint>
#include <functional>
#include <vector>

namespace obscura::usda {

namespace {

constexpr const char* kPrefix = "expressionVariables:";
constexpr int kMaxNesting = 64;

struct Result;
using List = std::vector<Result>;
struct Result {
    std::variant<std::monostate, std::string, int64_t, bool, List> v;
};

struct Failure {
    std::string message;
};

// The expression's tree: evaluated after parsing, so that if() and the logical functions take only
// the operands they need (if(defined(X), "${X}", "") must not substitute an undefined X).
struct Node {
    enum class Kind { Literal, Substituted, Variable, ListOf, Call, Name } kind = Kind::Literal;
    Result literal;
    std::string text;  // Substituted: the string with its ${...}; Variable, Name: the name; Call: the function
    std::vector<Node> args;
};

class Parser {
public:
    explicit Parser(std::string_view text) : text_(text) {}

    Node parse() {
        Node node = expression();
        blanks();
        if (pos_ != text_.size()) fail("unexpected '" + std::string(1, text_[pos_]) + "'");
        return node;
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw Failure{"column " + std::to_string(pos_ + 2) + ": " + what};  // +1 for the backtick
    }
    void blanks() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }
    bool at(char c) const { return pos_ < text_.size() && text_[pos_] == c; }

    Node expression() {
        if (++depth_ > kMaxNesting) fail("nested more than " + std::to_string(kMaxNesting) + " deep");
        Node node = primary();
        --depth_;
        return node;
    }

    Node primary() {
        blanks();
        if (pos_ == text_.size()) fail("expected a value");
        const char c = text_[pos_];
        if (c == '"' || c == '\'') return quoted(c);
        if (c == '$') {
            Node node{Node::Kind::Variable};
            node.text = variableName();
            return node;
        }
        if (c == '[') {
            ++pos_;
            Node node{Node::Kind::ListOf};
            blanks();
            while (!at(']')) {
                node.args.push_back(expression());
                blanks();
                if (at(',')) ++pos_;
                else if (!at(']')) fail("expected ',' or ']' in a list");
                blanks();
            }
            ++pos_;
            return node;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '-') {
            const size_t start = pos_++;
            while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
            Node node;
            try {
                node.literal.v = int64_t(std::stoll(std::string(text_.substr(start, pos_ - start))));
            } catch (...) {
                fail("not an integer");
            }
            return node;
        }
        const size_t start = pos_;
        while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
        const std::string word(text_.substr(start, pos_ - start));
        if (word.empty()) fail("unexpected '" + std::string(1, c) + "'");
        Node node;
        if (word == "None") return node;
        if (word == "true" || word == "True" || word == "false" || word == "False") {
            node.literal.v = word == "true" || word == "True";
            return node;
        }
        blanks();
        node.text = word;
        if (!at('(')) {  // a variable's name, as defined() takes them
            node.kind = Node::Kind::Name;
            return node;
        }
        ++pos_;
        node.kind = Node::Kind::Call;
        blanks();
        while (!at(')')) {
            node.args.push_back(expression());
            blanks();
            if (at(',')) ++pos_;
            else if (!at(')')) fail("expected ',' or ')' in the arguments of '" + word + "'");
            blanks();
        }
        ++pos_;
        return node;
    }

    // `${NAME}` at pos_.
    std::string variableName() {
        if (text_.compare(pos_, 2, "${") != 0) fail("expected '${'");
        const size_t close = text_.find('}', pos_);
        if (close == std::string_view::npos) fail("unclosed '${'");
        std::string name(text_.substr(pos_ + 2, close - pos_ - 2));
        if (name.empty()) fail("an empty variable name");
        pos_ = close + 1;
        return name;
    }

    // A quoted string, its escapes resolved; its ${NAME}s left for evaluation.
    Node quoted(char quote) {
        ++pos_;
        Node node{Node::Kind::Substituted};
        while (!at(quote)) {
            if (pos_ == text_.size()) fail("unterminated string");
            if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) {
                // An escaped '$' stays literal: it is marked so that substitution passes it by.
                node.text += text_[pos_ + 1] == '$' ? std::string("\\$") : std::string(1, text_[pos_ + 1]);
                pos_ += 2;
            } else {
                node.text += text_[pos_++];
            }
        }
        ++pos_;
        return node;
    }

    std::string_view text_;
    size_t pos_ = 0;
    int depth_ = 0;
};

Result fromValue(const Value& value) {
    auto element = [&](size_t i) -> Result {
        if (!value.strings.empty()) return {value.strings[i]};
        if (value.typeName == "bool") return {value.numbers[i] != 0.0};
        return {int64_t(value.numbers[i])};
    };
    if (!value.isArray) return value.size() > 0 ? element(0) : Result{};
    List list;
    for (size_t i = 0; i < value.size(); ++i) list.push_back(element(i));
    return {list};
}

class Evaluator {
public:
    explicit Evaluator(const ExpressionVariables& variables) : variables_(variables) {}

    Result eval(const Node& n) {
        switch (n.kind) {
        case Node::Kind::Literal: return n.literal;
        case Node::Kind::Variable: return variable(n.text);
        case Node::Kind::Substituted: return {substitute(n.text)};
        case Node::Kind::ListOf: {
            List list;
            for (const Node& a : n.args) list.push_back(eval(a));
            return {list};
        }
        case Node::Kind::Call: return call(n);
        case Node::Kind::Name: throw Failure{"'" + n.text + "' is neither a value nor a function call"};
        }
        return {};
    }

private:
    Result variable(const std::string& name) {
        const auto it = variables_.find(name);
        if (it == variables_.end()) throw Failure{"no expression variable '" + name + "'"};
        return fromValue(it->second);
    }

    std::string substitute(const std::string& s) {
        std::string out;
        for (size_t i = 0; i < s.size();) {
            if (s.compare(i, 2, "\\$") == 0) {
                out += '$';
                i += 2;
            } else if (s.compare(i, 2, "${") == 0) {
                const size_t close = s.find('}', i);
                if (close == std::string::npos) throw Failure{"unclosed '${' in a string"};
                const std::string name = s.substr(i + 2, close - i - 2);
                const Result value = variable(name);
                const auto* text = std::get_if<std::string>(&value.v);
                if (!text) throw Failure{"expression variable '" + name + "' is not a string"};
                out += *text;
                i = close + 1;
            } else {
                out += s[i++];
            }
        }
        return out;
    }

    bool truth(const Result& r, const std::string& function) {
        if (const auto* b = std::get_if<bool>(&r.v)) return *b;
        if (const auto* i = std::get_if<int64_t>(&r.v)) return *i != 0;
        throw Failure{function + "() takes booleans or integers"};
    }

    static bool equal(const Result& a, const Result& b) {
        if (a.v.index() != b.v.index()) return false;
        if (const auto* l = std::get_if<List>(&a.v)) {
            const List& m = std::get<List>(b.v);
            if (l->size() != m.size()) return false;
            for (size_t i = 0; i < l->size(); ++i)
                if (!equal((*l)[i], m[i])) return false;
            return true;
        }
        if (const auto* x = std::get_if<std::string>(&a.v)) return *x == std::get<std::string>(b.v);
        if (const auto* x = std::get_if<int64_t>(&a.v)) return *x == std::get<int64_t>(b.v);
        if (const auto* x = std::get_if<bool>(&a.v)) return *x == std::get<bool>(b.v);
        return true;  // both None
    }

    Result call(const Node& n) {
        const std::string& f = n.text;
        auto arity = [&](size_t low, size_t high) {
            if (n.args.size() < low || n.args.size() > high) throw Failure{f + "() takes " + std::to_string(low) +
                                                                           (high > low ? " or more" : "") + " arguments"};
        };
        if (f == "if") {
            arity(2, 3);
            if (truth(eval(n.args[0]), f)) return eval(n.args[1]);
            return n.args.size() == 3 ? eval(n.args[2]) : Result{};
        }
        if (f == "and" || f == "or") {
            arity(2, 1024);
            for (const Node& a : n.args)
                if (truth(eval(a), f) != (f == "and")) return {f == "or"};
            return {f == "and"};
        }
        if (f == "not") {
            arity(1, 1);
            return {!truth(eval(n.args[0]), f)};
        }
        if (f == "defined") {
            arity(1, 1024);
            for (const Node& a : n.args) {
                if (a.kind != Node::Kind::Name) throw Failure{"defined() takes variable names"};
                if (!variables_.count(a.text)) return {false};
            }
            return {true};
        }
        if (f == "eq" || f == "neq") {
            arity(2, 2);
            return {equal(eval(n.args[0]), eval(n.args[1])) == (f == "eq")};
        }
        if (f == "lt" || f == "leq" || f == "gt" || f == "geq") {
            arity(2, 2);
            const Result a = eval(n.args[0]), b = eval(n.args[1]);
            const auto* x = std::get_if<int64_t>(&a.v);
            const auto* y = std::get_if<int64_t>(&b.v);
            if (!x || !y) throw Failure{f + "() compares integers"};
            return {f == "lt" ? *x < *y : f == "leq" ? *x <= *y : f == "gt" ? *x > *y : *x >= *y};
        }
        if (f == "len") {
            arity(1, 1);
            const Result a = eval(n.args[0]);
            if (const auto* s = std::get_if<std::string>(&a.v)) return {int64_t(s->size())};
            if (const auto* l = std::get_if<List>(&a.v)) return {int64_t(l->size())};
            throw Failure{"len() takes a string or a list"};
        }
        if (f == "contains" || f == "at") {
            arity(2, 2);
            const Result a = eval(n.args[0]), b = eval(n.args[1]);
            if (f == "contains") {
                if (const auto* s = std::get_if<std::string>(&a.v)) {
                    const auto* sub = std::get_if<std::string>(&b.v);
                    if (!sub) throw Failure{"contains() looks for a string in a string"};
                    return {s->find(*sub) != std::string::npos};
                }
                if (const auto* l = std::get_if<List>(&a.v)) {
                    for (const Result& e : *l)
                        if (equal(e, b)) return {true};
                    return {false};
                }
                throw Failure{"contains() takes a string or a list"};
            }
            const auto* index = std::get_if<int64_t>(&b.v);
            if (!index) throw Failure{"at() takes an integer index"};
            const int64_t size = std::holds_alternative<std::string>(a.v) ? int64_t(std::get<std::string>(a.v).size())
                                 : std::holds_alternative<List>(a.v) ? int64_t(std::get<List>(a.v).size())
                                                                      : -1;
            if (size < 0) throw Failure{"at() takes a string or a list"};
            const int64_t i = *index < 0 ? size + *index : *index;
            if (i < 0 || i >= size) throw Failure{"at(): index " + std::to_string(*index) + " is outside"};
            if (const auto* s = std::get_if<std::string>(&a.v)) return {std::string(1, (*s)[size_t(i)])};
            return std::get<List>(a.v)[size_t(i)];
        }
        throw Failure{"unknown function '" + f + "'"};
    }

    const ExpressionVariables& variables_;
};

}  // namespace

ExpressionVariables expressionVariablesOf(const std::map<std::string, Value>& layerMetadata) {
    ExpressionVariables variables;
    for (auto it = layerMetadata.lower_bound(kPrefix);
         it != layerMetadata.end() && it->first.rfind(kPrefix, 0) == 0; ++it)
        variables[it->first.substr(std::string_view(kPrefix).size())] = it->second;
    return variables;
}

bool isVariableExpression(const std::string& text) {
    return text.size() >= 2 && text.front() == '`' && text.back() == '`';
}

std::variant<std::string, ExpressionProblem> evaluateVariableExpression(const std::string& text,
                                                                        const ExpressionVariables& variables) {
    try {
        const Node root = Parser(std::string_view(text).substr(1, text.size() - 2)).parse();
        const Result result = Evaluator(variables).eval(root);
        if (std::holds_alternative<std::monostate>(result.v)) return std::string();
        if (const auto* s = std::get_if<std::string>(&result.v)) return *s;
        return ExpressionProblem{"expression " + text + " is not a string"};
    } catch (const Failure& failure) {
        return ExpressionProblem{"expression " + text + ": " + failure.message};
    }
}

}  // namespace obscura::usda
