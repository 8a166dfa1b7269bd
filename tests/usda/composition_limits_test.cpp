// Composition has a budget (CompositionLimits): a small file whose arcs fan out must end in an
// Error naming where it grew, checked as the stage grows, never in an exhausted machine.
#include <string>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

const std::string kLaughs = test::kDataDir + "/limits/laughs.usda";
const std::string kRepeated = test::kDataDir + "/limits/repeated_reference.usda";

Error openFileError(const std::string& path, const CompositionLimits& limits) {
    auto result = Stage::open(path, StageOptions{limits, {}});
    if (const Error* error = std::get_if<Error>(&result)) return *error;
    ADD_FAILURE() << path << " composed within the limits";
    return Error{};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// 2.2 KB whose every level's two children reference the next: 2^18 prims, 8 GB if composed
// without a budget. The default limits stop it.
TEST(CompositionLimits, BillionLaughsStopsAtTheDefaultLimits) {
    const Error error = openFileError(kLaughs, CompositionLimits{});
    EXPECT_EQ(error.where.file, kLaughs);
    EXPECT_GE(error.where.line, 1) << error.str();
    EXPECT_TRUE(contains(error.message, "composition stopped")) << error.str();
}

TEST(CompositionLimits, PrimLimitIsSettableAndNamesThePrimThatPassesIt) {
    CompositionLimits limits;
    limits.maxPrims = 1000;
    const Error error = openFileError(kLaughs, limits);
    EXPECT_TRUE(contains(error.message, "would be prim 1001 of the stage; the limit is 1000 prims")) << error.str();
    // Blamed on a child spec inside one of the levels ("def Xform "a"" or "b", lines 14..), not
    // on the root's empty location.
    EXPECT_EQ(error.where.file, kLaughs);
    EXPECT_GE(error.where.line, 12) << error.str();
}

TEST(CompositionLimits, MemoryLimitIsSettable) {
    CompositionLimits limits;
    limits.maxMemoryBytes = size_t(16) << 20;
    const Error error = openFileError(kLaughs, limits);
    EXPECT_TRUE(contains(error.message, "more than 16 MiB (the memory limit)")) << error.str();
    EXPECT_GE(error.where.line, 1) << error.str();
}

// </T> names </N0> (8191 nodes) 1000 times: without a check before each copy that is 8 million
// nodes (6 GB) before the limit is looked at. The arc that passes the limit is blamed.
TEST(CompositionLimits, RepeatedReferenceFailsAtTheArcThatPassesTheIndexLimit) {
    const Error error = openFileError(kRepeated, CompositionLimits{});
    EXPECT_TRUE(contains(error.message, "more than 10000 composition arcs contribute to </T>")) << error.str();
    EXPECT_EQ(error.where.file, kRepeated);
    EXPECT_EQ(error.where.line, 7) << error.str();  // the references list of </T>
    EXPECT_GE(error.where.column, 19) << error.str();
}

TEST(CompositionLimits, IndexNodeLimitIsSettable) {
    CompositionLimits limits;
    limits.maxIndexNodes = 20000;
    // Twice 8191 fits under 20000; the third copy does not.
    const Error error = openFileError(kRepeated, limits);
    EXPECT_TRUE(contains(error.message, "more than 20000 composition arcs contribute to </T>")) << error.str();
}

// The error of a root prim used to print an empty location ("obscura: : more than ...").
TEST(CompositionLimits, RootPrimIndexErrorNamesTheFileLineAndColumn) {
    std::string text = "#usda 1.0\ndef \"Root\" (\n    references = [";
    for (int i = 0; i < 3; ++i) text += std::string(i ? ", " : "") + "</Big>";
    text += "]\n)\n{\n}\nclass \"Big\" (\n    references = [</A>, </B>]\n)\n{\n}\nclass \"A\"\n{\n}\nclass \"B\"\n{\n}\n";
    CompositionLimits limits;
    limits.maxIndexNodes = 8;  // Root + 3 x (Big, A, B) = 10 nodes
    auto result = Stage::openFromString(text, "root.usda", StageOptions{limits, {}});
    ASSERT_TRUE(std::holds_alternative<Error>(result));
    const Error& error = std::get<Error>(result);
    EXPECT_EQ(error.where.file, "root.usda");
    EXPECT_EQ(error.where.line, 3) << error.str();
    EXPECT_GE(error.where.column, 1) << error.str();
    EXPECT_TRUE(contains(error.message, "contribute to </Root>")) << error.str();
}

TEST(CompositionLimits, ScenesWithinTheLimitsCompose) {
    CompositionLimits limits;
    limits.maxPrims = 3;
    auto stage = Stage::openFromString("#usda 1.0\ndef \"A\"\n{\n    def \"B\"\n    {\n    }\n}\ndef \"C\"\n{\n}\n",
                                       "small.usda", StageOptions{limits, {}});
    EXPECT_TRUE(std::holds_alternative<std::unique_ptr<Stage>>(stage));
}

}  // namespace
}  // namespace obscura::usda
