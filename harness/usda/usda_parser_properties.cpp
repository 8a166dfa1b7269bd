// Attribute and relationship statements inside a prim.
#include "harness/usda/usda_keywords.h"
#include "harness/usda/usda_parser.h"

namespace obscura::usda {

std::string Parser::parseProperty(PrimSpec& prim, std::optional<Token> listOpToken) {
    if (!listOpToken && listOpKind(peek())) listOpToken = take();
    const bool custom = acceptWord("custom");
    bool uniform = false;
    if (peek().isWord("uniform") || peek().isWord("config")) {
        take();
        uniform = true;
    } else {
        acceptWord("varying");
    }
    std::string name;
    if (acceptWord("rel")) {
        parseRelationship(prim, listOpToken, custom, name);
    } else {
        parseAttribute(prim, listOpToken, custom, uniform, name);
    }
    return name;
}

void Parser::parseAttribute(PrimSpec& prim, const std::optional<Token>& listOpToken, bool custom, bool uniform,
                            std::string& name) {
    const Token typeToken = take();
    if (typeToken.kind != TokenKind::Identifier || isKeyword(typeToken.text))
        fail(typeToken, "expected an attribute type or 'rel', found " + describe(typeToken));
    const ValueType* type = findValueType(typeToken.text);
    if (!type) fail(typeToken, "unknown attribute type '" + std::string(typeToken.text) + "'");
    bool isArray = false;
    if (accept('[')) {
        expect(']', "after '" + std::string(type->name) + "['");
        isArray = true;
    }
    const std::string typeName = (uniform ? "uniform " : "") + std::string(type->name) + (isArray ? "[]" : "");
    const Token nameToken = take();
    if (nameToken.kind != TokenKind::Identifier)
        fail(nameToken, "expected an attribute name after type '" + typeName + "', found " + describe(nameToken));
    name = nameToken.text;
    if (prim.relationships.count(name)) fail(nameToken, "'" + name + "' is already a relationship of " + primPathText());

    AttributeSpec& attr = prim.attributes[name];
    if (attr.type && attr.typeName != typeName)
        fail(typeToken, "attribute '" + name + "' redeclared as '" + typeName + "' (was '" + attr.typeName + "')");
    attr.typeName = typeName;
    attr.type = type;
    attr.isArray = isArray;
    attr.isUniform = uniform;
    attr.isCustom = attr.isCustom || custom;
    attr.where = where(nameToken);

    if (accept('.')) {
        const Token field = take();
        if (field.isWord("timeSamples")) {
            if (listOpToken) fail(*listOpToken, "time samples cannot be list-edited");
            expect('=', "after '" + name + ".timeSamples'");
            attr.timeSamples = parseTimeSamples(*type, isArray);
        } else if (field.isWord("connect")) {
            expect('=', "after '" + name + ".connect'");
            const ListOpKind op = listOpToken ? *listOpKind(*listOpToken) : ListOpKind::Explicit;
            std::vector<std::string> targets;
            parseListOf("connections", op == ListOpKind::Explicit, [&] { targets.push_back(parsePath("connections")); });
            attr.connections.set(op, std::move(targets));
        } else if (field.isWord("spline")) {
            if (listOpToken) fail(*listOpToken, "splines cannot be list-edited");
            expect('=', "after '" + name + ".spline'");
            // A spline this reader cannot read (malformed, or of a form newer than its grammar) loses
            // the attribute only its spline, as bad prim data loses only that prim: the balanced
            // block is read past, and the problem reported where it lies.
            const Lexer atSpline = lexer_;
            std::shared_ptr<const Spline> spline;
            try {
                spline = parseSpline(*type);
            } catch (const ParseFailure& failure) {
                lexer_ = atSpline;
                skipBraceBlock("spline");
                warn("spline", field,
                     "attribute '" + name + "' of " + primPathText() + " has a spline that cannot be read (" +
                         failure.error.str() + "); its default and time samples are used");
                return;
            }
            if (std::string problem = spline->innerLoopProblem(); !problem.empty())
                warn("spline", field,
                     "attribute '" + name + "' of " + primPathText() + " has a spline that is left out: " + problem +
                         "; its default and time samples are used");
            else if (splineAnimates(type->name, isArray))
                attr.spline = std::move(spline);
            else
                warn("spline", field,
                     "attribute '" + name + "' of " + primPathText() + " is a " + typeName +
                         ", which no spline animates (double, float, half and timecode do); its default and time "
                         "samples are used");
        } else {
            fail(field, "expected 'timeSamples', 'connect' or 'spline' after '" + name + ".', found " + describe(field));
        }
        return;
    }
    if (listOpToken)
        fail(*listOpToken, "'" + std::string(listOpToken->text) +
                               "' applies only to relationships and attribute connections ('.connect')");
    if (accept('=')) {
        attr.animationBlock = acceptWord("AnimationBlock");
        if (attr.animationBlock)
            attr.defaultValue.reset();
        else
            attr.defaultValue = acceptWord("None") ? blockedValue(*type, isArray) : parseTypedValue(*type, isArray);
    } else if (!peek().isPunct('(') && !atStatementEnd()) {
        fail(peek(), "expected '=' or '(' after attribute name '" + name + "', found " + describe(peek()));
    }
    if (peek().isPunct('('))
        parseMetadataBlock("attribute '" + name + "'", [&] { parseMetadataItem(attr.metadata, nullptr); });
}

void Parser::parseRelationship(PrimSpec& prim, const std::optional<Token>& listOpToken, bool custom,
                               std::string& name) {
    const Token nameToken = take();
    if (nameToken.kind != TokenKind::Identifier)
        fail(nameToken, "expected a relationship name after 'rel', found " + describe(nameToken));
    name = nameToken.text;
    if (prim.attributes.count(name)) fail(nameToken, "'" + name + "' is already an attribute of " + primPathText());
    RelationshipSpec& rel = prim.relationships[name];
    rel.isCustom = rel.isCustom || custom;
    rel.where = where(nameToken);
    if (accept('=')) {
        const ListOpKind op = listOpToken ? *listOpKind(*listOpToken) : ListOpKind::Explicit;
        std::vector<std::string> targets;
        parseListOf("relationship targets", op == ListOpKind::Explicit,
                    [&] { targets.push_back(parsePath("relationship targets")); });
        rel.targets.set(op, std::move(targets));
    } else if (!peek().isPunct('(') && !atStatementEnd()) {
        fail(peek(), "expected '=' or '(' after relationship name '" + name + "', found " + describe(peek()));
    }
    if (peek().isPunct('('))
        parseMetadataBlock("relationship '" + name + "'", [&] { parseMetadataItem(rel.metadata, nullptr); });
}

}  // namespace obscura::usda
