// Reading what asset paths name (assets/asset_reader.h): plain files, files in USDZ packages and in
// packages inside packages, all in memory, and the reasons when something cannot be read.
#include "assets/asset_reader.h"
#include "assets/package_path.h"
#include "tests/support/usdz_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace obscura::test {
namespace {

namespace fs = std::filesystem;
using assets::joinPackagePath;

class AssetReaderTest : public ::testing::Test {
protected:
    AssetReaderTest() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("obscura_asset_reader_" + std::string(info->name()) + "_" +
                                            std::to_string(getpid()));
        fs::create_directories(dir_);
    }
    ~AssetReaderTest() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::string read(const std::string& assetPath) {
        std::string problem;
        auto bytes = assets_.read(assetPath, &problem);
        EXPECT_TRUE(bytes) << assetPath << ": " << problem;
        return bytes.value_or("");
    }
    std::string problemReading(const std::string& assetPath) {
        std::string problem;
        EXPECT_FALSE(assets_.read(assetPath, &problem)) << assetPath;
        return problem;
    }

    fs::path dir_;
    assets::AssetReader assets_;
};

TEST_F(AssetReaderTest, ReadsPlainFilesAndFilesInPackages) {
    std::ofstream(dir_ / "plain.txt") << "on disk";
    ASSERT_EQ(writeUsdz(dir_ / "a.usdz", {{"scene.usda", "#usda 1.0\n"}, {"tex/b.png", "packaged"}}), "");
    EXPECT_EQ(read(path("plain.txt")), "on disk");
    EXPECT_EQ(read(joinPackagePath(path("a.usdz"), "tex/b.png")), "packaged");
    std::string problem;
    const assets::UsdzPackage* package = assets_.package(path("a.usdz"), &problem);
    ASSERT_TRUE(package) << problem;
    EXPECT_EQ(package->rootLayer(), "scene.usda");
    EXPECT_EQ(package->entries(), (std::vector<std::string>{"scene.usda", "tex/b.png"}));
    EXPECT_EQ(assets_.package(path("a.usdz"), &problem), package);  // opened once
}

TEST_F(AssetReaderTest, ReadsFilesInAPackageInsideAPackage) {
    ASSERT_EQ(writeUsdz(dir_ / "inner.usdz", {{"c.png", "nested"}}), "");
    ASSERT_EQ(writeUsdz(dir_ / "outer.usdz", {{"inner.usdz", fileBytes(dir_ / "inner.usdz")}}), "");
    fs::remove(dir_ / "inner.usdz");
    EXPECT_EQ(read(path("outer.usdz[inner.usdz[c.png]]")), "nested");
    EXPECT_EQ(problemReading(path("outer.usdz[inner.usdz[d.png]]")), "no file 'd.png' in the package");
    EXPECT_EQ(problemReading(path("outer.usdz[missing.usdz[c.png]]")), "no file 'missing.usdz' in the package");
}

TEST_F(AssetReaderTest, SaysWhyWhatCannotBeRead) {
    ASSERT_EQ(writeUsdz(dir_ / "a.usdz", {{"b.png", "packaged"}}), "");
    std::ofstream(dir_ / "broken.usdz") << "not a zip archive";
    EXPECT_EQ(problemReading(path("missing.png")), "no such file");
    EXPECT_EQ(problemReading(dir_.string()), "cannot be read");  // a folder
    EXPECT_EQ(problemReading(joinPackagePath(path("a.usdz"), "c.png")), "no file 'c.png' in the package");
    EXPECT_EQ(problemReading(joinPackagePath(path("missing.usdz"), "b.png")), "no such file");
    const std::string broken = problemReading(joinPackagePath(path("broken.usdz"), "b.png"));
    EXPECT_EQ(broken.rfind("not a readable zip archive: ", 0), 0u) << broken;
    // A package that could not be opened is tried again.
    fs::rename(dir_ / "a.usdz", dir_ / "missing.usdz");
    EXPECT_EQ(read(joinPackagePath(path("missing.usdz"), "b.png")), "packaged");
}

}  // namespace
}  // namespace obscura::test
