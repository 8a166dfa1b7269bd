// No input may crash the reader: truncated files, random bytes, mutations and deep nesting all
// end in a Stage or an Error with a location inside the text.
#include <fstream>
#include <random>
#include <sstream>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using test::kDataDir;

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Lines as the lexer counts them: "\n", "\r\n" and a lone "\r" each end one.
int lineCount(const std::string& text) {
    int lines = 1;
    for (size_t i = 0; i < text.size(); ++i)
        lines += text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'));
    return lines;
}

// Opens `text` and checks the outcome is well formed; returns whether it composed.
bool openSafely(const std::string& text) {
    auto result = Stage::openFromString(text, "fuzz.usda");
    if (const Error* error = std::get_if<Error>(&result)) {
        EXPECT_FALSE(error->message.empty());
        EXPECT_EQ(error->where.file, "fuzz.usda");
        EXPECT_GE(error->where.line, 1);
        EXPECT_LE(error->where.line, lineCount(text));
        EXPECT_GE(error->where.column, 1);
        return false;
    }
    const Stage& stage = *std::get<std::unique_ptr<Stage>>(result);
    // Walking everything must be safe too.
    for (const Prim* prim : stage.prims()) {
        stage.worldTransform(*prim, 1.0);
        stage.isVisible(*prim, 1.0);
        for (const auto& entry : prim->attributes) entry.second.evaluate(12.5);
    }
    return true;
}

TEST(ParserRobustness, SampleFileComposes) {
    const std::string sample = readFile(kDataDir + "/robust_sample.usda");
    ASSERT_FALSE(sample.empty());
    EXPECT_TRUE(openSafely(sample));
}

TEST(ParserRobustness, TruncatedAtEveryByte) {
    const std::string sample = readFile(kDataDir + "/robust_sample.usda");
    ASSERT_FALSE(sample.empty());
    int composed = 0;
    for (size_t length = 0; length <= sample.size(); ++length) {
        SCOPED_TRACE(length);
        composed += openSafely(sample.substr(0, length));
    }
    // Cuts right after a complete top-level prim still compose; the rest are errors.
    EXPECT_GT(composed, 0);
    EXPECT_LT(composed, static_cast<int>(sample.size()));
}

TEST(ParserRobustness, RandomBytes) {
    std::mt19937 random(1234);
    for (int i = 0; i < 3000; ++i) {
        std::string text = (i % 2) ? "#usda 1.0\n" : "";
        const int length = static_cast<int>(random() % 200);
        for (int j = 0; j < length; ++j) text += static_cast<char>(random() % 256);
        openSafely(text);
    }
}

TEST(ParserRobustness, RandomGrammarSoup) {
    // Fragments of real syntax in random order reach much deeper into the parser than bytes.
    const std::vector<std::string> pieces = {
        "def ", "over ", "class ", "Xform ", "\"A\" ", "\"B\" ", "{", "}", "(", ")", "[", "]", "=", ",", ":", ";",
        ".", "\n", " ", "float ", "float3[] ", "token ", "rel ", "custom ", "uniform ", "prepend ", "None ",
        "references = ", "@a.usda@", "</A>", "<../B.x>", "1", "-2.5e3", "inf", "\"s\"", "\"\"\"t\"\"\"",
        "variantSet ", "variants = { string v = \"x\" }", "x.timeSamples = ", "x.connect = ", "{ string k = \"v\" }",
        "kind = \"component\"", "inherits = </A>", "#c\n", "/* c */", "@@@q@@@", "dictionary ",
    };
    std::mt19937 random(99);
    for (int i = 0; i < 4000; ++i) {
        std::string text = "#usda 1.0\n";
        const int count = static_cast<int>(random() % 60);
        for (int j = 0; j < count; ++j) text += pieces[random() % pieces.size()];
        openSafely(text);
    }
}

TEST(ParserRobustness, MutatedSample) {
    const std::string sample = readFile(kDataDir + "/robust_sample.usda");
    const std::string alphabet = "{}()[]<>@\"'=,:;.#/\n -0123456789abcXYZ\\";
    std::mt19937 random(7);
    for (int i = 0; i < 1500; ++i) {
        std::string text = sample;
        const int edits = 1 + static_cast<int>(random() % 4);
        for (int e = 0; e < edits; ++e) text[random() % text.size()] = alphabet[random() % alphabet.size()];
        openSafely(text);
    }
}

TEST(ParserRobustness, DeepPrimNestingIsAnError) {
    std::string text = "#usda 1.0\n";
    for (int i = 0; i < 100000; ++i) text += "def \"a\" {\n";
    const Error error = test::openError(text, "fuzz.usda");
    EXPECT_NE(error.message.find("nesting deeper than"), std::string::npos) << error.str();
}

TEST(ParserRobustness, ModerateNestingIsFine) {
    std::string text = "#usda 1.0\n";
    for (int i = 0; i < 150; ++i) text += "def \"a\"\n{\n";
    for (int i = 0; i < 150; ++i) text += "}\n";
    const auto stage = test::open(text);
    ASSERT_TRUE(stage);
    EXPECT_EQ(stage->prims().size(), 150u);
}

TEST(ParserRobustness, DeepValueAndDictionaryNestingIsAnError) {
    std::string tuples = "#usda 1.0\ndef \"A\" (\n    x = " + std::string(100000, '(') + "\n)\n{\n}\n";
    EXPECT_FALSE(openSafely(tuples));
    std::string dictionaries = "#usda 1.0\ndef \"A\" (\n    customData = ";
    for (int i = 0; i < 50000; ++i) dictionaries += "{ dictionary d = ";
    EXPECT_FALSE(openSafely(dictionaries));
    std::string arrays = "#usda 1.0\ndef \"A\"\n{\n    float[] x = " + std::string(100000, '[') + "\n}\n";
    EXPECT_FALSE(openSafely(arrays));
}

TEST(ParserRobustness, ExponentialReferenceFanOutFailsInsteadOfHanging) {
    // Every level references both prims of the next: 2^30 paths to the bottom.
    std::string text = "#usda 1.0\n";
    for (int level = 0; level < 30; ++level) {
        const std::string next = std::to_string(level + 1);
        for (const char* side : {"a", "b"})
            text += "def \"L" + std::to_string(level) + side + "\" (\n    references = [</L" + next + "a>, </L" + next +
                    "b>]\n)\n{\n}\n";
    }
    text += "def \"L30a\"\n{\n}\ndef \"L30b\"\n{\n}\n";
    const Error error = test::openError(text, "fuzz.usda");
    EXPECT_NE(error.message.find("composition arcs contribute"), std::string::npos) << error.str();
}

}  // namespace
}  // namespace obscura::usda
