// Variant fallbacks from plugInfo.json files on a PXR_PLUGINPATH_NAME-style search path
// (harness/plugin_variant_fallbacks.h): folders and files, Includes with wildcards, the last
// plugin read winning a set, and malformed files or entries reported where they are and ignored.
#include "harness/plugin_variant_fallbacks.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace obscura::test {
namespace {

namespace fs = std::filesystem;

// A folder of plugInfo.json files, removed at the end.
struct PluginFolder {
    fs::path root = fs::temp_directory_path() / ("obscura_plug_fallbacks_" + std::to_string(::getpid()) + "_" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    PluginFolder() { fs::create_directories(root); }
    ~PluginFolder() { fs::remove_all(root); }
    fs::path write(const std::string& relative, const std::string& text) const {
        const fs::path file = root / relative;
        fs::create_directories(file.parent_path());
        std::ofstream(file) << text;
        return file;
    }
};

std::string plugin(const std::string& fallbacks, const std::string& includes = "") {
    return "# a comment, as OpenUSD allows\n{\n" + (includes.empty() ? "" : "  \"Includes\": [" + includes + "],\n") +
           "  \"Plugins\": [{\"Type\": \"resource\", \"Name\": \"looks\", \"Info\": {\"UsdVariantFallbacks\": " +
           fallbacks + "}}]\n}\n";
}

TEST(PluginVariantFallbacks, ReadFromFoldersFilesAndIncludes) {
    PluginFolder folder;
    folder.write("a/plugInfo.json", plugin(R"({"shadingVariant": ["Default", "Plain"], "lod": ["high"]})",
                                           R"("../more/*/", "missing/plugInfo.json")"));
    folder.write("more/one/plugInfo.json", plugin(R"({"lod": ["low"]})"));
    const fs::path file = folder.write("b.json", plugin(R"({"modelingVariant": ["Box"]})"));
    const harness::PluginVariantFallbacks read =
        harness::readPluginVariantFallbacks((folder.root / "a").string() + "::" + file.string() + ":/no/such/folder");
    EXPECT_TRUE(read.warnings.empty());
    EXPECT_EQ(read.fallbacks, (usda::VariantFallbacks{{"shadingVariant", {"Default", "Plain"}},
                                                      {"lod", {"low"}},  // the included plugin is read later
                                                      {"modelingVariant", {"Box"}}}));
}

TEST(PluginVariantFallbacks, AMalformedFileIsReportedWhereItIsAndIgnored) {
    PluginFolder folder;
    const fs::path bad = folder.write("bad/plugInfo.json", "{\n  \"Plugins\": [\n    {\"Info\": }\n  ]\n}\n");
    folder.write("good/plugInfo.json", plugin(R"({"lod": ["high"]})"));
    const harness::PluginVariantFallbacks read =
        harness::readPluginVariantFallbacks((folder.root / "bad").string() + ":" + (folder.root / "good").string());
    ASSERT_EQ(read.warnings.size(), 1u);
    EXPECT_EQ(read.warnings[0].where.file, bad.string());
    EXPECT_EQ(read.warnings[0].where.line, 3);
    EXPECT_EQ(read.warnings[0].where.column, 14) << "the unexpected '}': " << read.warnings[0].message;
    EXPECT_NE(read.warnings[0].message.find("malformed plugInfo.json"), std::string::npos) << read.warnings[0].message;
    EXPECT_EQ(read.fallbacks, (usda::VariantFallbacks{{"lod", {"high"}}}));
}

TEST(PluginVariantFallbacks, EntriesThatAreNotVariantListsAreReportedAndIgnored) {
    PluginFolder folder;
    const fs::path file = folder.write("plugInfo.json", plugin(R"({"lod": "high", "shadingVariant": ["Default"]})"));
    folder.write("other/plugInfo.json", plugin(R"(["lod"])"));
    const harness::PluginVariantFallbacks read =
        harness::readPluginVariantFallbacks(folder.root.string() + ":" + (folder.root / "other").string());
    ASSERT_EQ(read.warnings.size(), 2u);
    EXPECT_EQ(read.warnings[0].where.file, file.string());
    EXPECT_NE(read.warnings[0].message.find("UsdVariantFallbacks.lod is not a list of variant names"), std::string::npos)
        << read.warnings[0].message;
    EXPECT_NE(read.warnings[1].message.find("UsdVariantFallbacks is not a map"), std::string::npos)
        << read.warnings[1].message;
    EXPECT_EQ(read.fallbacks, (usda::VariantFallbacks{{"shadingVariant", {"Default"}}}));
}

}  // namespace
}  // namespace obscura::test
