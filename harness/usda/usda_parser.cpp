#include "harness/usda/usda_parser.h"

#include <cstdio>

#include "harness/usda/sdf_path.h"
#include "harness/usda/usda_keywords.h"

namespace obscura::usda {

namespace {

// Deeper prim/variant/dictionary nesting than this is rejected rather than recursed into.
constexpr int kMaxNesting = 200;

bool isPrimKeyword(const Token& token) {
    return token.isWord("def") || token.isWord("over") || token.isWord("class");
}

std::string locationText(const Token& token) {
    return std::to_string(token.line) + ":" + std::to_string(token.column);
}

}  // namespace

std::variant<std::unique_ptr<Layer>, Error> parseLayer(std::string_view text, const std::string& identifier) {
    try {
        return Parser(text, identifier).parse();
    } catch (const ParseFailure& failure) {
        return failure.error;
    }
}

Parser::Parser(std::string_view text, std::string identifier)
    : lexer_(text), identifier_(std::move(identifier)), layer_(std::make_unique<Layer>()) {
    layer_->identifier = identifier_;
}

Parser::NestingGuard::NestingGuard(Parser& parser, const Token& at) : parser_(parser) {
    if (++parser_.depth_ > kMaxNesting) {
        --parser_.depth_;
        parser_.fail(at, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
    }
}

// ---- Tokens ----------------------------------------------------------------------------------

const Token& Parser::peek() {
    const Token& token = lexer_.peek();
    if (token.kind == TokenKind::Error) fail(token, token.value);
    return token;
}

Token Parser::take() {
    peek();
    return lexer_.next();
}

Token Parser::expect(char punct, const std::string& context) {
    if (!peek().isPunct(punct))
        fail(peek(), std::string("expected '") + punct + "' " + context + ", found " + describe(peek()));
    return take();
}

bool Parser::accept(char punct) {
    if (!peek().isPunct(punct)) return false;
    take();
    return true;
}

bool Parser::acceptWord(std::string_view word) {
    if (!peek().isWord(word)) return false;
    take();
    return true;
}

void Parser::skipNewlines() {
    while (peek().kind == TokenKind::Newline) take();
}

bool Parser::atStatementEnd() {
    const Token& token = peek();
    return token.kind == TokenKind::Newline || token.kind == TokenKind::EndOfFile || token.isPunct(';');
}

void Parser::endStatement(const std::string& what) {
    const Token& token = peek();
    if (token.isPunct(';') || token.kind == TokenKind::Newline) {
        take();
        skipNewlines();
        return;
    }
    // At the end of the file the enclosing prim reports its missing '}'.
    if (token.kind == TokenKind::EndOfFile) return;
    fail(token, "expected end of line or ';' after " + what + ", found " + describe(token));
}

void Parser::endBlock(const std::string& what) {
    const Token& token = peek();
    if (token.kind == TokenKind::Newline) {
        skipNewlines();
        return;
    }
    if (token.kind == TokenKind::EndOfFile) return;
    fail(token, "expected end of line after " + what + ", found " + describe(token));
}

void Parser::fail(const Token& at, const std::string& message) const {
    throw ParseFailure{Error{where(at), message}};
}

SourceLocation Parser::where(const Token& token) const {
    return SourceLocation{identifier_, token.line, token.column};
}

void Parser::warn(const std::string& kind, const Token& at, const std::string& message) {
    layer_->diagnostics.push_back(Diagnostic{kind, Warning{where(at), message}});
}

// ---- Layer -------------------------------------------------------------------------------------

std::unique_ptr<Layer> Parser::parse() {
    const Token& magic = peek();
    if (magic.kind != TokenKind::Magic || magic.text.substr(0, 6) != "#usda ")
        fail(magic, "expected '#usda 1.0' on the first line, found " + describe(magic));
    const Token header = take();
    std::string_view version = header.text.substr(6);
    while (!version.empty() && (version.back() == ' ' || version.back() == '\t')) version.remove_suffix(1);
    if (version != "1.0") warn("version", header, "unexpected usda version '" + std::string(version) + "'; read as 1.0");

    skipNewlines();
    if (peek().isPunct('(')) {
        parseMetadataBlock("the layer", [this] { parseLayerMetadataItem(); });
        skipNewlines();
    }
    while (peek().kind != TokenKind::EndOfFile) {
        const Token& token = peek();
        if (isPrimKeyword(token)) {
            const std::string path = parsePrim(layer_->pseudoRoot);
            endBlock("prim <" + path + ">");
        } else if (token.isWord("reorder")) {
            const Token reorder = take();
            if (!acceptWord("rootPrims")) fail(peek(), "expected 'rootPrims' after 'reorder', found " + describe(peek()));
            expect('=', "after 'reorder rootPrims'");
            parseListOf("rootPrims", false, [this] { parseName("rootPrims"); });
            warn("reorder", reorder, "'reorder' statements are ignored");
            endStatement("'reorder rootPrims'");
        } else {
            fail(token, "expected 'def', 'over' or 'class', found " + describe(token));
        }
    }
    return std::move(layer_);
}

void Parser::parseLayerMetadataItem() {
    parseMetadataItem(layer_->metadata, [this](const Token& key, ListOpKind op) {
        if (!key.isWord("subLayers")) return false;
        if (op != ListOpKind::Explicit) fail(key, "subLayers cannot be list-edited");
        parseListOf("subLayers", false, [this] {
            const Token asset = take();
            if (asset.kind != TokenKind::AssetPath || asset.value.empty())
                fail(asset, "expected an asset path '@...@' in subLayers, found " + describe(asset));
            layer_->subLayers.push_back(Reference{asset.value, "", where(asset)});
            if (peek().isPunct('('))
                layer_->subLayers.back().layerOffset = parseArcParameters("sublayer @" + asset.value + "@", false);
        });
        return true;
    });
}

// ---- Prims -------------------------------------------------------------------------------------

std::string Parser::parsePrim(PrimSpec& parent) {
    const Token keyword = take();
    NestingGuard guard(*this, keyword);
    auto spec = std::make_unique<PrimSpec>();
    spec->specifier = keyword.isWord("def") ? Specifier::Def : keyword.isWord("class") ? Specifier::Class : Specifier::Over;
    spec->where = where(keyword);
    std::string written(keyword.text);
    if (peek().kind == TokenKind::Identifier) {
        const Token type = take();
        if (isKeyword(type.text)) fail(type, "expected a prim type or a quoted prim name, found " + describe(type));
        spec->typeName = type.text;
        // Python-qualified type names ("Module.Type") are part of the grammar.
        while (accept('.')) spec->typeName += "." + parseName("prim type name");
        written += " " + spec->typeName;
    }
    const Token nameToken = take();
    if (nameToken.kind != TokenKind::String)
        fail(nameToken, "expected a quoted prim name after '" + written + "', found " + describe(nameToken));
    if (const size_t bad = sdfpath::invalidUtf8At(nameToken.value); bad != std::string_view::npos) {
        char byte[8];
        std::snprintf(byte, sizeof(byte), "0x%02X", static_cast<unsigned char>(nameToken.value[bad]));
        fail(nameToken, "prim name has an invalid UTF-8 byte " + std::string(byte) + " at offset " + std::to_string(bad));
    }
    if (!sdfpath::isIdentifier(nameToken.value)) fail(nameToken, "'" + nameToken.value + "' is not a valid prim name");
    const std::string path = sdfpath::appendChild(primPath_, nameToken.value);
    if (parent.child(nameToken.value)) fail(nameToken, "duplicate prim <" + path + ">");
    spec->name = nameToken.value;

    const std::string parentPath = primPath_;
    primPath_ = path;
    skipNewlines();
    if (peek().isPunct('(')) {
        parseMetadataBlock("prim <" + path + ">", [&] { parsePrimMetadataItem(*spec); });
        skipNewlines();
    }
    const Token open = expect('{', "to open prim <" + path + ">");
    parsePrimContents(*spec, open, "prim <" + path + ">");
    primPath_ = parentPath;

    parent.childByName[spec->name] = spec.get();
    parent.children.push_back(std::move(spec));
    return path;
}

void Parser::parsePrimContents(PrimSpec& prim, const Token& open, const std::string& what) {
    skipNewlines();
    for (;;) {
        const Token& token = peek();
        if (token.isPunct('}')) {
            take();
            return;
        }
        if (token.kind == TokenKind::EndOfFile)
            fail(token, "expected '}' to close " + what + " opened at " + locationText(open) + ", found end of file");
        if (isPrimKeyword(token)) {
            const std::string path = parsePrim(prim);
            endBlock("prim <" + path + ">");
        } else if (token.isWord("variantSet")) {
            const std::string name = parseVariantSet(prim);
            endBlock("variantSet \"" + name + "\"");
        } else if (token.isWord("reorder")) {
            Token reorder = take();
            if (peek().isWord("nameChildren") || peek().isWord("properties")) {
                const std::string list(take().text);
                expect('=', "after 'reorder " + list + "'");
                parseListOf(list, false, [this, &list] { parseName(list); });
                warn("reorder", reorder, "'reorder' statements are ignored");
                endStatement("'reorder " + list + "'");
            } else {
                const std::string name = parseProperty(prim, std::move(reorder));
                endStatement("property '" + name + "'");
            }
        } else {
            const std::string name = parseProperty(prim, std::nullopt);
            endStatement("property '" + name + "'");
        }
    }
}

void Parser::parsePrimMetadataItem(PrimSpec& prim) {
    parseMetadataItem(prim.metadata, [this, &prim](const Token& key, ListOpKind op) { return parsePrimArc(prim, key, op); });
}

bool Parser::parsePrimArc(PrimSpec& prim, const Token& key, ListOpKind op) {
    const bool isExplicit = op == ListOpKind::Explicit;
    const std::string name(key.text);
    if (name == "references" || name == "payload") {
        std::vector<Reference> items;
        parseListOf(name, isExplicit, [&] { items.push_back(parseReferenceItem(name)); });
        (name == "references" ? prim.references : prim.payloads).set(op, std::move(items));
        return true;
    }
    if (name == "inherits" || name == "specializes") {
        std::vector<Reference> items;
        parseListOf(name, isExplicit, [&] {
            const Token& at = peek();
            const SourceLocation location = where(at);
            items.push_back(Reference{"", parsePath(name), location});
        });
        (name == "inherits" ? prim.inherits : prim.specializes).set(op, std::move(items));
        return true;
    }
    if (name == "apiSchemas" || name == "variantSets") {
        std::vector<std::string> names;
        parseListOf(name, isExplicit, [&] { names.push_back(parseName(name)); });
        // Variant sets are known from their variantSet blocks, so only apiSchemas is kept.
        if (name == "apiSchemas") prim.apiSchemas.set(op, std::move(names));
        return true;
    }
    if (name == "variants") {
        if (!isExplicit) fail(key, "variant selections cannot be list-edited");
        std::map<std::string, Value> selections;
        parseDictionary("", selections);
        for (const auto& [set, value] : selections)
            if (value.strings.size() == 1 && !value.isArray) prim.variantSelections[set] = value.strings.front();
        return true;
    }
    return false;
}

std::string Parser::parseVariantSet(PrimSpec& prim) {
    const Token keyword = take();
    NestingGuard guard(*this, keyword);
    const Token nameToken = take();
    if (nameToken.kind != TokenKind::String)
        fail(nameToken, "expected a quoted variant set name after 'variantSet', found " + describe(nameToken));
    const std::string setName = nameToken.value;
    expect('=', "after variantSet \"" + setName + "\"");
    skipNewlines();
    expect('{', "to open variantSet \"" + setName + "\"");
    skipNewlines();
    VariantSetSpec& set = prim.variantSets[setName];
    while (!peek().isPunct('}')) {
        const Token variantToken = take();
        if (variantToken.kind != TokenKind::String)
            fail(variantToken, "expected a quoted variant name in variantSet \"" + setName + "\", found " +
                                   describe(variantToken));
        const std::string what = "variant \"" + variantToken.value + "\" of variantSet \"" + setName + "\"";
        if (set.variants.count(variantToken.value)) fail(variantToken, "duplicate " + what);
        auto contents = std::make_unique<PrimSpec>();
        contents->name = variantToken.value;
        contents->where = where(variantToken);
        skipNewlines();
        if (peek().isPunct('(')) {
            parseMetadataBlock(what, [&] { parsePrimMetadataItem(*contents); });
            skipNewlines();
        }
        const Token open = expect('{', "to open " + what);
        parsePrimContents(*contents, open, what);
        skipNewlines();
        set.variants[variantToken.value] = std::move(contents);
    }
    take();
    return setName;
}

}  // namespace obscura::usda
