// Recursive-descent parser for USD's text format, following Pixar's grammar (sdf/textFileFormat.yy):
// newlines separate statements, metadata lists take ';' or newlines, values may span lines.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "harness/usda/layer.h"
#include "harness/usda/usda_lexer.h"

namespace obscura::usda {

// Parses one layer; `identifier` names the file in locations and anchors its asset paths.
std::variant<std::unique_ptr<Layer>, Error> parseLayer(std::string_view text, const std::string& identifier);

// Thrown inside the parser and caught by parseLayer: a syntax error ends the parse.
struct ParseFailure {
    Error error;
};

class Parser {
public:
    Parser(std::string_view text, std::string identifier);
    std::unique_ptr<Layer> parse();

private:
    // Handles metadata a generic "key = value" cannot (composition arcs, sublayers); returns
    // false for keys it does not own.
    using SpecialMetadata = std::function<bool(const Token& key, ListOpKind op)>;

    // Bounds recursion so that deeply nested input fails cleanly instead of exhausting the stack.
    class NestingGuard {
    public:
        NestingGuard(Parser& parser, const Token& at);
        ~NestingGuard() { --parser_.depth_; }
        NestingGuard(const NestingGuard&) = delete;
        NestingGuard& operator=(const NestingGuard&) = delete;

    private:
        Parser& parser_;
    };

    // Tokens (usda_parser.cpp)
    const Token& peek();
    Token take();
    Token expect(char punct, const std::string& context);
    bool accept(char punct);
    bool acceptWord(std::string_view word);
    void skipNewlines();
    bool atStatementEnd();
    void endStatement(const std::string& what);
    void endBlock(const std::string& what);
    [[noreturn]] void fail(const Token& at, const std::string& message) const;
    SourceLocation where(const Token& token) const;
    void warn(const std::string& kind, const Token& at, const std::string& message);
    std::string primPathText() const { return "<" + primPath_ + ">"; }

    // Layer, prims and properties (usda_parser.cpp)
    void parseLayerMetadataItem();
    std::string parsePrim(PrimSpec& parent);
    void parsePrimContents(PrimSpec& prim, const Token& open, const std::string& what);
    void parsePrimMetadataItem(PrimSpec& prim);
    bool parsePrimArc(PrimSpec& prim, const Token& key, ListOpKind op);
    std::string parseVariantSet(PrimSpec& prim);
    std::string parseProperty(PrimSpec& prim, std::optional<Token> listOpToken);
    void parseAttribute(PrimSpec& prim, const std::optional<Token>& listOpToken, bool custom, bool uniform,
                        std::string& name);
    void parseRelationship(PrimSpec& prim, const std::optional<Token>& listOpToken, bool custom, std::string& name);

    // Metadata and lists (usda_parser_metadata.cpp)
    void parseMetadataBlock(const std::string& owner, const std::function<void()>& item);
    void parseMetadataItem(std::map<std::string, Value>& metadata, const SpecialMetadata& special);
    void parseMetadataValue(const std::string& key, std::map<std::string, Value>& metadata);
    void parseDictionary(const std::string& prefix, std::map<std::string, Value>& out);
    std::vector<std::pair<Token, Token>> parseColonMap(const std::string& what);
    void parseListOf(const std::string& what, bool allowNone, const std::function<void()>& item);
    Reference parseReferenceItem(const std::string& what);
    LayerOffset parseArcParameters(const std::string& what, bool allowCustomData);
    std::string parsePath(const std::string& what);
    std::string parseName(const std::string& what);

    // Values (usda_parser_values.cpp)
    Value parseTypedValue(const ValueType& type, bool isArray);
    Value blockedValue(const ValueType& type, bool isArray) const;
    void parseElement(const ValueType& type, Value& out);
    void parseScalar(const ValueType& type, Value& out);
    void parseTuple(int count, std::string_view typeName, bool isMatrixRow, const std::function<void()>& component);
    double parseTimeCode();
    double toNumber(const Token& token) const;
    std::map<double, Value> parseTimeSamples(const ValueType& type, bool isArray);
    // Splines (usda_parser_spline.cpp)
    std::shared_ptr<const Spline> parseSpline(const ValueType& type);
    // Reads past a balanced { ... } block (a spline this reader cannot read).
    void skipBraceBlock(const std::string& what);
    double parseSplineNumber(const std::string& what);
    int parseSplineLoopCount(const std::string& what);
    SplineExtrapolation parseSplineExtrapolation(const Token& mode);
    SplineLoop parseSplineLoop();
    // A knot's tangent `form(numbers)` on its pre or post side; a Hermite's Maya height waits in
    // `hermiteHeight` for the knot's neighbours.
    void parseSplineKnotTangent(bool isPre, bool hermite, SplineKnot& knot, std::optional<double>& hermiteHeight);
    Value parseInferredValue();

    Lexer lexer_;
    std::string identifier_;
    std::unique_ptr<Layer> layer_;
    std::string primPath_ = "/";  // the prim being parsed (variant selections left out): anchors relative paths
    int depth_ = 0;
};

}  // namespace obscura::usda
