// Package paths (assets/package_path.h), the syntax the harness writes and the plugin reads:
// split and joined as OpenUSD's Ar does, nested packages included, and anchored as its default
// resolver anchors asset paths.
#include "assets/package_path.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace obscura::test {
namespace {

using assets::absoluteAssetPath;
using assets::anchorAssetPath;
using assets::joinPackagePath;
using assets::splitPackagePath;

void expectSplit(const std::string& path, const std::string& package, const std::string& entry) {
    const auto split = splitPackagePath(path);
    ASSERT_TRUE(split) << path;
    EXPECT_EQ(split->package, package) << path;
    EXPECT_EQ(split->entry, entry) << path;
    EXPECT_EQ(joinPackagePath(split->package, split->entry), path);
}

TEST(PackagePath, SplitsTheInnermostPackageFromTheFileInIt) {
    expectSplit("/dir/a.usdz[tex/b.png]", "/dir/a.usdz", "tex/b.png");
    expectSplit("a.usdz[b.usdz[c.png]]", "a.usdz[b.usdz]", "c.png");
    expectSplit("a.usdz[b.usdz[c.usdz[d/e.png]]]", "a.usdz[b.usdz[c.usdz]]", "d/e.png");
    // Brackets elsewhere in a path are names, not packages.
    expectSplit("/scenes[old]/a.usdz[tex/b.png]", "/scenes[old]/a.usdz", "tex/b.png");
    expectSplit("a.usdz[tex/b.<UDIM>.png]", "a.usdz", "tex/b.<UDIM>.png");
}

TEST(PackagePath, PathsThatNameNoFileInAPackage) {
    for (const char* path : {"/dir/a.png", "a.usdz", "/dir[x]/a.png", "[b.png]", "a.usdz[]", "a.usdz]b.png]", ""})
        EXPECT_FALSE(splitPackagePath(path)) << path;
}

TEST(PackagePath, JoiningIntoANestedPackageNestsTheFile) {
    EXPECT_EQ(joinPackagePath("a.usdz", "b.png"), "a.usdz[b.png]");
    EXPECT_EQ(joinPackagePath("a.usdz[b.usdz]", "c.png"), "a.usdz[b.usdz[c.png]]");
}

TEST(PackagePath, AnchorsRelativeAssetsToTheLayer) {
    // A layer on disk: its folder.
    EXPECT_EQ(anchorAssetPath("tex/b.png", "/dir/scene.usda"), "/dir/tex/b.png");
    EXPECT_EQ(anchorAssetPath("../b.png", "/dir/sub/scene.usda"), "/dir/b.png");
    EXPECT_EQ(anchorAssetPath("/abs/./b.png", "/dir/scene.usda"), "/abs/b.png");
    // A layer in a package: its folder in the package.
    EXPECT_EQ(anchorAssetPath("tex/b.png", "/dir/a.usdz[scenes/s.usda]"), "/dir/a.usdz[scenes/tex/b.png]");
    EXPECT_EQ(anchorAssetPath("../b.png", "/dir/a.usdz[scenes/s.usda]"), "/dir/a.usdz[b.png]");
    EXPECT_EQ(anchorAssetPath("/abs/b.png", "/dir/a.usdz[s.usda]"), "/abs/b.png");
    // A package path: its package anchored like any asset, the file inside as written.
    EXPECT_EQ(anchorAssetPath("other.usdz[tex/./b.png]", "/dir/scene.usda"), "/dir/other.usdz[tex/b.png]");
    EXPECT_EQ(anchorAssetPath("inner.usdz[b.png]", "/dir/a.usdz[s/s.usda]"), "/dir/a.usdz[s/inner.usdz[b.png]]");
    EXPECT_EQ(anchorAssetPath("b.png", "/dir/a.usdz[inner.usdz[s.usda]]"), "/dir/a.usdz[inner.usdz[b.png]]");
    // Relative layers anchor relatively.
    EXPECT_EQ(anchorAssetPath("b.png", "scenes/a.usdz[s.usda]"), "scenes/a.usdz[b.png]");
}

TEST(PackagePath, AbsolutePathsMakeOnlyTheOutermostFileAbsolute) {
    const std::string cwd = std::filesystem::current_path().string();
    EXPECT_EQ(absoluteAssetPath("/dir/../b.png"), "/b.png");
    EXPECT_EQ(absoluteAssetPath("scenes/./b.png"), cwd + "/scenes/b.png");
    // The file inside is kept as it is: ".." there is no folder of the disk.
    EXPECT_EQ(absoluteAssetPath("a.usdz[../b.png]"), cwd + "/a.usdz[../b.png]");
    EXPECT_EQ(absoluteAssetPath("x/../a.usdz[b.usdz[c.png]]"), cwd + "/a.usdz[b.usdz[c.png]]");
}

}  // namespace
}  // namespace obscura::test
