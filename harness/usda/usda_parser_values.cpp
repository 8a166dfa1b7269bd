// Values: typed (an attribute's or dictionary entry's declared type drives the parse, so large
// arrays go straight into a Value) and inferred (untyped metadata, typed by what is written).
#include <charconv>
#include <cmath>
#include <limits>

#include "harness/usda/sdf_path.h"
#include "harness/usda/usda_parser.h"

namespace obscura::usda {

namespace {

bool isIntegerLiteral(std::string_view text) {
    return text.find_first_of(".eEin") == std::string_view::npos;
}

std::string expectation(ScalarKind kind) {
    switch (kind) {
    case ScalarKind::Bool: return "true, false, 0 or 1";
    case ScalarKind::Integer: return "an integer";
    case ScalarKind::Real: return "a number";
    case ScalarKind::String:
    case ScalarKind::Token: return "a quoted string";
    case ScalarKind::Asset: return "an asset path '@...@'";
    }
    return "a value";
}

}  // namespace

double Parser::toNumber(const Token& token) const {
    std::string_view text = token.text;
    if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (text == "inf") return std::numeric_limits<double>::infinity();
    if (text == "-inf") return -std::numeric_limits<double>::infinity();
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc::result_out_of_range) fail(token, "number " + describe(token) + " is out of range");
    if (ec != std::errc() || end != text.data() + text.size()) fail(token, "malformed number " + describe(token));
    return value;
}

Value Parser::blockedValue(const ValueType& type, bool isArray) const {
    Value value;
    value.typeName = type.name;
    value.isArray = isArray;
    value.tupleSize = type.tupleSize;
    value.blocked = true;
    return value;
}

Value Parser::parseTypedValue(const ValueType& type, bool isArray) {
    Value value = blockedValue(type, isArray);
    value.blocked = false;
    const std::string name(type.name);
    if (!isArray) {
        parseElement(type, value);
        return value;
    }
    expect('[', "to open a " + name + "[] value");
    skipNewlines();
    while (!peek().isPunct(']')) {
        parseElement(type, value);
        skipNewlines();
        if (accept(',')) {
            skipNewlines();
        } else if (!peek().isPunct(']')) {
            fail(peek(), "expected ',' or ']' in " + name + "[] value, found " + describe(peek()));
        }
    }
    take();
    return value;
}

void Parser::parseElement(const ValueType& type, Value& out) {
    if (type.tupleSize == 1) {
        parseScalar(type, out);
    } else if (type.rows > 0) {
        parseTuple(type.rows, type.name, false, [&] { parseTuple(type.rows, type.name, true, [&] { parseScalar(type, out); }); });
    } else {
        parseTuple(type.tupleSize, type.name, false, [&] { parseScalar(type, out); });
    }
}

// Messages are only built on failure: this runs for every element of large arrays.
void Parser::parseTuple(int count, std::string_view typeName, bool isMatrixRow, const std::function<void()>& component) {
    auto what = [&] { return (isMatrixRow ? "row of " : "") + std::string(typeName); };
    if (!peek().isPunct('(')) fail(peek(), "expected '(' to open a " + what() + " value, found " + describe(peek()));
    take();
    for (int i = 0; i < count; ++i) {
        skipNewlines();
        if (i > 0) {
            if (peek().isPunct(')'))
                fail(peek(), "too few components in " + what() + " value: expected " + std::to_string(count) +
                                 ", found " + std::to_string(i));
            if (!accept(','))
                fail(peek(), "expected ',' between components of a " + what() + " value, found " + describe(peek()));
            skipNewlines();
        }
        component();
    }
    skipNewlines();
    if (accept(',')) skipNewlines();
    if (!peek().isPunct(')'))
        fail(peek(), "expected ')' after " + std::to_string(count) + " components of a " + what() + " value, found " +
                         describe(peek()));
    take();
}

void Parser::parseScalar(const ValueType& type, Value& out) {
    const Token token = take();
    switch (type.scalar) {
    case ScalarKind::String:
    case ScalarKind::Token:
        if (token.kind == TokenKind::String) return out.strings.edit().push_back(token.value);
        break;
    case ScalarKind::Asset:
        if (token.kind == TokenKind::AssetPath) return out.strings.edit().push_back(token.value);
        break;
    case ScalarKind::Bool:
        if (token.isWord("true") || token.isWord("false")) return out.numbers.edit().push_back(token.isWord("true") ? 1.0 : 0.0);
        if (token.kind == TokenKind::Number && (token.text == "0" || token.text == "1"))
            return out.numbers.edit().push_back(toNumber(token));
        break;
    case ScalarKind::Integer:
        if (token.kind == TokenKind::Number && isIntegerLiteral(token.text)) return out.numbers.edit().push_back(toNumber(token));
        break;
    case ScalarKind::Real:
        if (token.kind == TokenKind::Number || token.isWord("inf") || token.isWord("nan"))
            return out.numbers.edit().push_back(toNumber(token));
        break;
    }
    fail(token, "expected " + expectation(type.scalar) + " for " + std::string(type.name) + ", found " + describe(token));
}

double Parser::parseTimeCode() {
    const Token token = take();
    if (token.kind != TokenKind::Number && !token.isWord("inf") && !token.isWord("nan"))
        fail(token, "expected a time code or '}' in time samples, found " + describe(token));
    return toNumber(token);
}

std::map<double, Value> Parser::parseTimeSamples(const ValueType& type, bool isArray) {
    expect('{', "to open time samples");
    skipNewlines();
    std::map<double, Value> samples;
    while (!peek().isPunct('}')) {
        const double time = parseTimeCode();
        expect(':', "after time code");
        samples[time] = acceptWord("None") ? blockedValue(type, isArray) : parseTypedValue(type, isArray);
        skipNewlines();
        if (accept(',')) {
            skipNewlines();
        } else if (!peek().isPunct('}')) {
            fail(peek(), "expected ',' or '}' after a time sample, found " + describe(peek()));
        }
    }
    take();
    return samples;
}

Value Parser::parseInferredValue() {
    // One kind of atom per value; numbers and bools mix (bools read as 0/1).
    enum class Kind { Unknown, Number, Bool, String, Token, Asset, Path };
    Kind kind = Kind::Unknown;
    bool integers = true;
    int rows = 0;  // rows of a nested tuple (a matrix)
    Value value;

    auto atom = [&] {
        const Token token = take();
        Kind found = Kind::Unknown;
        if (token.kind == TokenKind::Number || token.isWord("inf") || token.isWord("nan")) {
            found = Kind::Number;
            integers = integers && isIntegerLiteral(token.text);
            value.numbers.edit().push_back(toNumber(token));
        } else if (token.isWord("true") || token.isWord("false")) {
            found = Kind::Bool;
            value.numbers.edit().push_back(token.isWord("true") ? 1.0 : 0.0);
        } else if (token.kind == TokenKind::Identifier) {
            found = Kind::Token;
            value.strings.edit().emplace_back(token.text);
        } else if (token.kind == TokenKind::String) {
            found = Kind::String;
            value.strings.edit().push_back(token.value);
        } else if (token.kind == TokenKind::AssetPath) {
            found = Kind::Asset;
            value.strings.edit().push_back(token.value);
        } else if (token.kind == TokenKind::PathRef) {
            found = Kind::Path;
            const std::optional<std::string> path = sdfpath::makeAbsolute(token.value, primPath_);
            if (token.value.empty() || !path) fail(token, "invalid path " + describe(token));
            value.strings.edit().push_back(*path);
        } else {
            fail(token, "expected a value, found " + describe(token));
        }
        const bool numeric = found == Kind::Number || found == Kind::Bool;
        const bool wasNumeric = kind == Kind::Number || kind == Kind::Bool;
        if (kind == Kind::Unknown || (numeric && kind == Kind::Bool)) {
            kind = found;
        } else if (found != kind && !(numeric && wasNumeric)) {
            fail(token, "value mixes different kinds of elements at " + describe(token));
        }
    };
    // A tuple: atoms, or tuples of atoms (matrix rows); returns the number of atoms.
    auto tuple = [&](auto& self, int level) -> int {
        const Token open = take();
        if (level > 1) fail(open, "tuples nested more than two deep");
        int atoms = 0;
        int nestedRows = 0;
        skipNewlines();
        while (!peek().isPunct(')')) {
            if (peek().isPunct('(')) {
                atoms += self(self, level + 1);
                ++nestedRows;
            } else {
                atom();
                ++atoms;
            }
            skipNewlines();
            if (accept(',')) {
                skipNewlines();
            } else if (!peek().isPunct(')')) {
                fail(peek(), "expected ',' or ')' in tuple, found " + describe(peek()));
            }
        }
        take();
        if (level == 0) rows = nestedRows;
        return atoms;
    };
    auto element = [&]() -> int {
        if (peek().isPunct('(')) return tuple(tuple, 0);
        if (peek().isPunct('[')) fail(peek(), "nested lists are not supported");
        atom();
        return 1;
    };

    int tupleSize = 0;
    if (accept('[')) {
        value.isArray = true;
        skipNewlines();
        while (!peek().isPunct(']')) {
            const Token first = peek();
            const int size = element();
            if (tupleSize != 0 && size != tupleSize)
                fail(first, "list elements have different sizes (" + std::to_string(tupleSize) + " and " +
                                std::to_string(size) + ")");
            tupleSize = size;
            skipNewlines();
            if (accept(',')) {
                skipNewlines();
            } else if (!peek().isPunct(']')) {
                fail(peek(), "expected ',' or ']' in list, found " + describe(peek()));
            }
        }
        take();
    } else {
        tupleSize = element();
    }
    value.tupleSize = std::max(tupleSize, 1);

    switch (kind) {
    case Kind::Unknown: break;  // an empty list
    case Kind::Number: {
        const std::string base = integers ? "int" : "double";
        if (rows > 0 && rows * rows == tupleSize) {
            value.typeName = "matrix" + std::to_string(rows) + "d";
        } else if (tupleSize >= 2 && tupleSize <= 4) {
            value.typeName = base + std::to_string(tupleSize);
        } else {
            value.typeName = base;
        }
        break;
    }
    case Kind::Bool: value.typeName = "bool"; break;
    case Kind::String: value.typeName = "string"; break;
    case Kind::Token: value.typeName = "token"; break;
    case Kind::Asset: value.typeName = "asset"; break;
    case Kind::Path: value.typeName = "path"; break;
    }
    return value;
}

}  // namespace obscura::usda
