// Metadata blocks "( ... )", dictionaries, and the list forms shared by arcs, targets and names.
#include <array>
#include <cmath>
#include <utility>

#include "harness/usda/sdf_path.h"
#include "harness/usda/usda_keywords.h"
#include "harness/usda/usda_parser.h"

namespace obscura::usda {

namespace {

// Metadata whose type USD fixes; any other key gets the type its value looks like.
const ValueType* metadataType(std::string_view key) {
    constexpr std::array<std::pair<std::string_view, std::string_view>, 19> kTypes = {{
        {"active", "bool"},
        {"hidden", "bool"},
        {"instanceable", "bool"},
        {"kind", "token"},
        {"elementSize", "int"},
        {"interpolation", "token"},
        {"displayName", "string"},
        {"displayGroup", "string"},
        {"documentation", "string"},
        {"colorSpace", "token"},
        {"upAxis", "token"},
        {"defaultPrim", "token"},
        {"renderSettingsPrimPath", "string"},
        {"metersPerUnit", "double"},
        {"timeCodesPerSecond", "double"},
        {"framesPerSecond", "double"},
        {"startTimeCode", "double"},
        {"endTimeCode", "double"},
        {"permission", "token"},
    }};
    for (const auto& [name, type] : kTypes)
        if (name == key) return findValueType(type);
    return nullptr;
}

Value stringValue(std::string typeName, std::string text) {
    Value value;
    value.typeName = std::move(typeName);
    value.strings.edit().push_back(std::move(text));
    return value;
}

}  // namespace

void Parser::parseMetadataBlock(const std::string& owner, const std::function<void()>& item) {
    const Token open = take();
    skipNewlines();
    while (!peek().isPunct(')')) {
        if (peek().kind == TokenKind::EndOfFile)
            fail(peek(), "expected ')' to close the metadata of " + owner + " opened at " + std::to_string(open.line) +
                             ":" + std::to_string(open.column) + ", found end of file");
        item();
        if (peek().isPunct(')')) break;
        if (peek().isPunct(';') || peek().kind == TokenKind::Newline) {
            take();
            skipNewlines();
        } else {
            fail(peek(), "expected ';', end of line or ')' after metadata of " + owner + ", found " + describe(peek()));
        }
    }
    take();
}

void Parser::parseMetadataItem(std::map<std::string, Value>& metadata, const SpecialMetadata& special) {
    if (peek().kind == TokenKind::String) {
        metadata["comment"] = stringValue("string", take().value);
        return;
    }
    std::optional<Token> listOpToken;
    ListOpKind op = ListOpKind::Explicit;
    if (const std::optional<ListOpKind> kind = listOpKind(peek())) {
        listOpToken = take();
        op = *kind;
    }
    const Token key = take();
    if (key.kind != TokenKind::Identifier) fail(key, "expected a metadata name, found " + describe(key));
    const std::string name = key.isWord("doc") ? "documentation" : std::string(key.text);
    expect('=', "after metadata name '" + std::string(key.text) + "'");
    if (special && special(key, op)) return;
    if (name == "relocates") {
        // Source and target paths, anchored to the prim they are authored on, in pairs.
        std::vector<std::string> paths;
        for (const auto& [source, target] : parseColonMap(name)) {
            const auto from = sdfpath::makeAbsolute(source.value, primPath_);
            const auto to = sdfpath::makeAbsolute(target.value, primPath_);
            if (source.kind != TokenKind::PathRef || target.kind != TokenKind::PathRef || !from || !to)
                fail(source, "expected prim paths '<...>: <...>' in relocates");
            paths.insert(paths.end(), {*from, *to});
        }
        Value pairs = stringValue("relocates", "");
        pairs.strings = std::move(paths);
        metadata[name] = std::move(pairs);
        return;
    }
    if (name == "prefixSubstitutions" || name == "suffixSubstitutions") {
        parseColonMap(name);
        warn("ignoredMetadata", key, "'" + name + "' metadata is not supported; ignored");
        return;
    }
    if (listOpToken) {
        parseListOf(name, op == ListOpKind::Explicit, [this] { parseInferredValue(); });
        warn("listEditedMetadata", *listOpToken, "list-edited metadata '" + name + "' is not supported; ignored");
        return;
    }
    parseMetadataValue(name, metadata);
}

void Parser::parseMetadataValue(const std::string& key, std::map<std::string, Value>& metadata) {
    if (peek().isPunct('{')) {
        parseDictionary(key + ":", metadata);
    } else if (acceptWord("None")) {
        metadata.erase(key);
    } else if (const ValueType* type = metadataType(key)) {
        metadata[key] = parseTypedValue(*type, false);
    } else {
        metadata[key] = parseInferredValue();
    }
}

void Parser::parseDictionary(const std::string& prefix, std::map<std::string, Value>& out) {
    NestingGuard guard(*this, peek());
    expect('{', "to open a dictionary");
    skipNewlines();
    while (!peek().isPunct('}')) {
        const Token typeToken = take();
        if (typeToken.kind != TokenKind::Identifier)
            fail(typeToken, "expected a value type or '}' in dictionary, found " + describe(typeToken));
        if (typeToken.isWord("dictionary")) {
            const std::string key = parseName("dictionary");
            expect('=', "after dictionary key '" + key + "'");
            parseDictionary(prefix + key + ":", out);
        } else {
            const ValueType* type = findValueType(typeToken.text);
            if (!type) fail(typeToken, "unknown value type '" + std::string(typeToken.text) + "' in dictionary");
            const bool isArray = accept('[');
            if (isArray) expect(']', "after '" + std::string(type->name) + "['");
            const std::string key = parseName("dictionary");
            expect('=', "after dictionary key '" + key + "'");
            out[prefix + key] = parseTypedValue(*type, isArray);
        }
        if (peek().isPunct('}')) break;
        if (!peek().isPunct(';') && peek().kind != TokenKind::Newline)
            fail(peek(), "expected ';', end of line or '}' after dictionary entry, found " + describe(peek()));
        take();
        skipNewlines();
    }
    take();
}

// { <a>: <b>, "x": "y" } as used by relocates and prefix/suffix substitutions.
std::vector<std::pair<Token, Token>> Parser::parseColonMap(const std::string& what) {
    std::vector<std::pair<Token, Token>> entries;
    expect('{', "to open " + what);
    skipNewlines();
    while (!peek().isPunct('}')) {
        Token sides[2];
        for (int side = 0; side < 2; ++side) {
            sides[side] = take();
            if (sides[side].kind != TokenKind::PathRef && sides[side].kind != TokenKind::String)
                fail(sides[side], "expected a path or string in " + what + ", found " + describe(sides[side]));
            if (side == 0) expect(':', "in " + what);
        }
        entries.emplace_back(sides[0], sides[1]);
        skipNewlines();
        if (accept(',')) {
            skipNewlines();
        } else if (!peek().isPunct('}')) {
            fail(peek(), "expected ',' or '}' in " + what + ", found " + describe(peek()));
        }
    }
    take();
    return entries;
}

void Parser::parseListOf(const std::string& what, bool allowNone, const std::function<void()>& item) {
    if (peek().isWord("None")) {
        const Token none = take();
        if (!allowNone) fail(none, "None is only allowed when " + what + " are set explicitly");
        return;
    }
    if (!accept('[')) {
        item();
        return;
    }
    skipNewlines();
    while (!peek().isPunct(']')) {
        item();
        skipNewlines();
        if (accept(',')) {
            skipNewlines();
        } else if (!peek().isPunct(']')) {
            fail(peek(), "expected ',' or ']' in " + what + ", found " + describe(peek()));
        }
    }
    take();
}

Reference Parser::parseReferenceItem(const std::string& what) {
    const Token token = take();
    Reference ref;
    ref.where = where(token);
    if (token.kind == TokenKind::AssetPath) {
        if (token.value.empty())
            fail(token, "empty asset path in " + what + " (an internal arc is written without '@...@')");
        ref.assetPath = token.value;
        if (peek().kind == TokenKind::PathRef) {
            const Token path = take();
            if (path.value.empty() || path.value[0] != '/')
                fail(path, "expected an absolute prim path in " + what + ", found " + describe(path));
            ref.primPath = path.value;
        }
    } else if (token.kind == TokenKind::PathRef) {
        const std::optional<std::string> path = sdfpath::makeAbsolute(token.value, primPath_);
        if (token.value.empty() || !path) fail(token, "invalid prim path " + describe(token) + " in " + what);
        ref.primPath = *path;
    } else {
        fail(token, "expected an asset path '@...@' or a prim path '<...>' in " + what + ", found " + describe(token));
    }
    if (peek().isPunct('(')) ref.layerOffset = parseArcParameters(what, true);
    return ref;
}

// ( offset = 10; scale = 2; customData = {...} ) after a reference, payload or sublayer.
LayerOffset Parser::parseArcParameters(const std::string& what, bool allowCustomData) {
    LayerOffset layerOffset;
    parseMetadataBlock(what, [&] {
        const Token key = take();
        if (key.isWord("offset") || key.isWord("scale")) {
            expect('=', "after '" + std::string(key.text) + "'");
            const Token number = take();
            if (number.kind != TokenKind::Number) fail(number, "expected a number, found " + describe(number));
            const double value = toNumber(number);
            // As Pcp does with an offset it cannot invert: reported, and the arc kept without it.
            if (!std::isfinite(value) || (key.isWord("scale") && value == 0.0))
                warn("layerOffset", number, "invalid layer " + std::string(key.text) + " in " + what +
                                                ": a layer offset must be finite and its scale other than 0; ignored");
            else
                (key.isWord("offset") ? layerOffset.offset : layerOffset.scale) = value;
        } else if (allowCustomData && key.isWord("customData")) {
            expect('=', "after 'customData'");
            std::map<std::string, Value> ignored;
            parseDictionary("", ignored);
        } else {
            fail(key, "expected 'offset' or 'scale' in the parameters of " + what + ", found " + describe(key));
        }
    });
    return layerOffset;
}

std::string Parser::parsePath(const std::string& what) {
    const Token token = take();
    if (token.kind != TokenKind::PathRef) fail(token, "expected a path '<...>' in " + what + ", found " + describe(token));
    const std::optional<std::string> path = sdfpath::makeAbsolute(token.value, primPath_);
    if (token.value.empty() || !path) fail(token, "invalid path " + describe(token) + " in " + what);
    return *path;
}

std::string Parser::parseName(const std::string& what) {
    const Token token = take();
    if (token.kind == TokenKind::String) return token.value;
    if (token.kind == TokenKind::Identifier) return std::string(token.text);
    fail(token, "expected a name in " + what + ", found " + describe(token));
}

}  // namespace obscura::usda
