// Malformed input: each error names the file, the line and column of the offending token, and
// what was expected there.
#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using test::kDataDir;
using test::openError;

struct ErrorCase {
    const char* name;
    std::string text;
    int line;
    int column;
    std::string message;
};

const std::vector<ErrorCase>& errorCases() {
    static const std::vector<ErrorCase> cases = {
        {"attribute name followed by brace",
         "#usda 1.0\ndef Mesh \"M\"\n{\n    point3f[] points }\n",
         4, 22, "expected '=' or '(' after attribute name 'points', found '}'"},
        {"missing header",
         "def \"A\"\n{\n}\n",
         1, 1, "expected '#usda 1.0' on the first line, found 'def'"},
        {"empty file",
         "",
         1, 1, "expected '#usda 1.0' on the first line, found end of file"},
        {"unterminated string",
         "#usda 1.0\ndef \"A\"\n{\n    string s = \"abc\n}\n",
         4, 16, "unterminated string"},
        {"unterminated triple-quoted string",
         "#usda 1.0\ndef \"A\" (\n    doc = \"\"\"never\nclosed\n)\n{\n}\n",
         3, 11, "unterminated triple-quoted string"},
        {"unterminated asset path",
         "#usda 1.0\ndef \"A\"\n{\n    asset a = @tex.png\n}\n",
         4, 15, "unterminated asset path"},
        {"too few tuple components",
         "#usda 1.0\ndef \"A\"\n{\n    float3 v = (1, 2)\n}\n",
         4, 21, "too few components in float3 value: expected 3, found 2"},
        {"too many tuple components",
         "#usda 1.0\ndef \"A\"\n{\n    float2 v = (1, 2, 3)\n}\n",
         4, 23, "expected ')' after 2 components of a float2 value, found '3'"},
        {"unknown attribute type",
         "#usda 1.0\ndef \"A\"\n{\n    floot x = 1\n}\n",
         4, 5, "unknown attribute type 'floot'"},
        {"missing closing brace",
         "#usda 1.0\ndef \"A\"\n{\n    float x = 1\n",
         5, 1, "expected '}' to close prim </A> opened at 3:1, found end of file"},
        {"invalid prim name",
         "#usda 1.0\ndef \"1abc\"\n{\n}\n",
         2, 5, "'1abc' is not a valid prim name"},
        {"unexpected character",
         "#usda 1.0\ndef \"A\"\n{\n    float a = $\n}\n",
         4, 15, "unexpected character '$'"},
        {"metadata without '='",
         "#usda 1.0\ndef \"A\" (\n    kind \"component\"\n)\n{\n}\n",
         3, 10, "expected '=' after metadata name 'kind', found string \"component\""},
        {"integer expected",
         "#usda 1.0\ndef \"A\"\n{\n    int i = 1.5\n}\n",
         4, 13, "expected an integer for int, found '1.5'"},
        {"bool expected",
         "#usda 1.0\ndef \"A\"\n{\n    bool b = 2\n}\n",
         4, 14, "expected true, false, 0 or 1 for bool, found '2'"},
        {"wrong element kind in array",
         "#usda 1.0\ndef \"A\"\n{\n    token[] t = [\"a\", 1]\n}\n",
         4, 23, "expected a quoted string for token, found '1'"},
        {"two statements on one line",
         "#usda 1.0\ndef \"A\"\n{\n    float a = 1 float b = 2\n}\n",
         4, 17, "expected end of line or ';' after property 'a', found 'float'"},
        {"time sample without colon",
         "#usda 1.0\ndef \"A\"\n{\n    float t.timeSamples = { 0 1 }\n}\n",
         4, 31, "expected ':' after time code, found '1'"},
        {"duplicate prim",
         "#usda 1.0\ndef \"A\"\n{\n}\ndef \"A\"\n{\n}\n",
         5, 5, "duplicate prim </A>"},
        {"child prim closed on the parent's line",
         "#usda 1.0\ndef \"A\"\n{\n    def \"B\" {}}\n",
         4, 15, "expected end of line after prim </A/B>, found '}'"},
        {"list op on a plain attribute",
         "#usda 1.0\ndef \"A\"\n{\n    prepend float x = 1\n}\n",
         4, 5, "'prepend' applies only to relationships and attribute connections ('.connect')"},
        {"relative path above the root",
         "#usda 1.0\ndef \"A\"\n{\n    rel r = <../../x>\n}\n",
         4, 13, "invalid path '<../../x>' in relationship targets"},
        {"statement that is not a prim",
         "#usda 1.0\nfloat x = 1\n",
         2, 1, "expected 'def', 'over' or 'class', found 'float'"},
        {"unclosed metadata",
         "#usda 1.0\ndef \"A\" (\n    kind = \"x\"\n",
         4, 1, "expected ')' to close the metadata of prim </A> opened at 2:9, found end of file"},
        {"None in a list edit",
         "#usda 1.0\ndef \"A\" (\n    prepend references = None\n)\n{\n}\n",
         3, 26, "None is only allowed when references are set explicitly"},
        {"empty asset path in references",
         "#usda 1.0\ndef \"A\" (\n    references = @@\n)\n{\n}\n",
         3, 18, "empty asset path in references (an internal arc is written without '@...@')"},
        {"spline block that is not closed",
         "#usda 1.0\ndef \"A\"\n{\n    double x.spline = { 1: (2 }\n}\n",
         4, 31, "unbalanced '}' in the spline"},
        {"unterminated block comment",
         "#usda 1.0\n/* open\ndef \"A\"\n{\n}\n",
         2, 1, "unterminated /* comment"},
        // Well-formed UTF-8 ("Caf\xc3\xa9") is a name; a stray byte, an overlong form or a surrogate is not.
        {"invalid UTF-8 byte in a prim name",
         "#usda 1.0\ndef \"Caf\xc3\xa9\"\n{\n}\ndef \"Bad\xff" "Name\"\n{\n}\n",
         5, 5, "prim name has an invalid UTF-8 byte 0xFF at offset 3"},
        {"overlong UTF-8 in a prim name",
         "#usda 1.0\ndef \"A\xc0\xaf" "B\"\n{\n}\n",
         2, 5, "prim name has an invalid UTF-8 byte 0xC0 at offset 1"},
        {"UTF-16 surrogate in a prim name",
         "#usda 1.0\ndef \"A\xed\xa0\x80\"\n{\n}\n",
         2, 5, "prim name has an invalid UTF-8 byte 0xED at offset 1"},
        {"truncated UTF-8 sequence in a prim name",
         "#usda 1.0\ndef \"A\xe2\x82\"\n{\n}\n",
         2, 5, "prim name has an invalid UTF-8 byte 0xE2 at offset 1"},
    };
    return cases;
}

TEST(ParserErrors, ReportFileLineColumnAndMessage) {
    for (const ErrorCase& c : errorCases()) {
        SCOPED_TRACE(c.name);
        const Error error = openError(c.text);
        EXPECT_EQ(error.where.file, "scene.usda");
        EXPECT_EQ(error.where.line, c.line);
        EXPECT_EQ(error.where.column, c.column);
        EXPECT_EQ(error.message, c.message);
    }
}

TEST(ParserErrors, StrFormatsFileLineColumnMessage) {
    const Error error = openError(errorCases().front().text);
    EXPECT_EQ(error.str(), "scene.usda:4:22: expected '=' or '(' after attribute name 'points', found '}'");
    const Error noLocation{SourceLocation{"a.usda", 0, 0}, "cannot open file"};
    EXPECT_EQ(noLocation.str(), "a.usda: cannot open file");
}

TEST(ParserErrors, MissingRootFile) {
    auto result = Stage::open(kDataDir + "/does/not/exist.usda");
    ASSERT_TRUE(std::holds_alternative<Error>(result));
    const Error& error = std::get<Error>(result);
    EXPECT_EQ(error.where.file, kDataDir + "/does/not/exist.usda");
    EXPECT_EQ(error.message, "cannot open file");
}

// The stage opens without the layer (tests/usda/missing_layers_test.cpp); the warning at the
// reference carries the error where it is in that layer.
TEST(ParserErrors, SyntaxErrorInAReferencedLayerPointsIntoThatLayer) {
    auto result = Stage::open(kDataDir + "/errors/bad_syntax_ref.usda");
    ASSERT_TRUE(std::holds_alternative<std::unique_ptr<Stage>>(result));
    const auto& stage = std::get<std::unique_ptr<Stage>>(result);
    ASSERT_EQ(stage->warnings().size(), 1u);
    const Warning& warning = stage->warnings().front();
    EXPECT_EQ(warning.where.file, kDataDir + "/errors/bad_syntax_ref.usda");
    EXPECT_EQ(warning.where.line, 4);
    EXPECT_EQ(warning.message, "reference of </Root> to @broken.usda@ ignored: " + kDataDir +
                                   "/errors/broken.usda:5:15: expected a number for float, found end of line");
    EXPECT_TRUE(stage->find("/Root"));
}

}  // namespace
}  // namespace obscura::usda
