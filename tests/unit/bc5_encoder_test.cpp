// BC5 (3Dc) normal-map compression (Kaplanyan 2010, "3Dc encoder improvements"): the encoder
// that minimises the angle of the reconstructed normal against the common per-channel one, on the
// corpus's real normal maps.
#include "delegate/bc5_encoder.h"
#include "delegate/cache_folder.h"
#include "delegate/normal_map_image.h"
#include "delegate/texture_disk_cache.h"
#include "tests/support/usdz_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace obscura::delegate {
namespace {

TEST(Bc5Encoder, BlocksDecodeToTheirPalettes) {
    // A constant normal lands on an endpoint: both encoders decode it to within the 8-bit
    // quantisation of x and y, under 0.3 degrees for a normal 30 degrees off z.
    const float tilt = 30.0f * 3.14159265f / 180.0f;
    NormalImage image{6, 5, std::vector<std::array<float, 3>>(30, {std::sin(tilt), 0.0f, std::cos(tilt)})};
    for (Bc5Encoder encoder : {Bc5Encoder::PerChannel, Bc5Encoder::NormalAware}) {
        auto blocks = encodeBc5(image, encoder);
        EXPECT_EQ(blocks.size(), 2u * 2u * 16u);
        const AngularError error = angularError(image, decodeBc5(blocks, 6, 5));
        EXPECT_LT(error.maxDegrees, 0.3);
    }
}

// Every normal map of the corpus: the normal-aware encoder's mean and maximum angular errors are
// never above the per-channel encoder's (it starts from that encoding and keeps only what lowers
// a block's summed angle without raising its largest), and the numbers go to bench/RESULTS.md.
TEST(Bc5Encoder, NormalAwareNeverErrsMoreThanPerChannelOnTheCorpus) {
    const std::filesystem::path corpus(OBSCURA_CORPUS_DIR);
    if (!std::filesystem::exists(corpus)) GTEST_SKIP() << "no corpus at " << corpus;
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(corpus)) {
        const std::string name = entry.path().filename().string(), ext = entry.path().extension().string();
        if (entry.is_regular_file() && name.find("normal_map") != std::string::npos && ext == ".png")
            files.push_back(entry.path());
        if (entry.is_regular_file() && name.find("_normal.") != std::string::npos && ext == ".jpg")
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty());
    std::printf("| normal map | size | per-channel mean / max | normal-aware mean / max | encode time |\n");
    for (const auto& file : files) {
        auto decoded = decodeNormalMap(test::fileBytes(file));
        ASSERT_TRUE(std::holds_alternative<NormalMapSource>(decoded)) << file;
        const NormalImage& reference = std::get<NormalMapSource>(decoded).normals;
        const auto common = angularError(
            reference, decodeBc5(encodeBc5(reference, Bc5Encoder::PerChannel), reference.width, reference.height));
        const auto start = std::chrono::steady_clock::now();
        const auto blocks = encodeBc5(reference, Bc5Encoder::NormalAware);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const auto improved = angularError(reference, decodeBc5(blocks, reference.width, reference.height));
        std::printf("| %s | %ux%u | %.3f / %.2f | %.3f / %.2f | %.1f s |\n", file.filename().string().c_str(),
                    reference.width, reference.height, common.meanDegrees, common.maxDegrees, improved.meanDegrees,
                    improved.maxDegrees, seconds);
        EXPECT_LE(improved.meanDegrees, common.meanDegrees) << file;
        EXPECT_LE(improved.maxDegrees, common.maxDegrees) << file;
    }
}

TEST(TextureDiskCache, KeysFollowTheContentAndOffWritesNothing) {
    const auto dir = std::filesystem::temp_directory_path() / ("obscura_texture_cache_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    // Two files of one content (wherever they lie: on disk, in a package) and one of another.
    const std::string a = TextureDiskCache::contentHash("one"), b = TextureDiskCache::contentHash("one"),
                      c = TextureDiskCache::contentHash("two");
    EXPECT_EQ(TextureDiskCache::key({a}, "bc5"), TextureDiskCache::key({b}, "bc5"));
    EXPECT_NE(TextureDiskCache::key({a}, "bc5"), TextureDiskCache::key({c}, "bc5"));
    EXPECT_NE(TextureDiskCache::key({a}, "bc5"), TextureDiskCache::key({a}, "bc5-2"));
    // Several files (a UDIM set's tiles): each file's content and their order.
    EXPECT_NE(TextureDiskCache::key({a, c}, "bc5"), TextureDiskCache::key({c, a}, "bc5"));
    EXPECT_NE(TextureDiskCache::key({a, c}, "bc5"), TextureDiskCache::key({a}, "bc5"));

    const std::vector<std::byte> bytes = {std::byte{1}, std::byte{0}, std::byte{255}};
    TextureDiskCache cache(dir / "cache");
    EXPECT_FALSE(cache.read(TextureDiskCache::key({a}, "bc5")));
    cache.write(TextureDiskCache::key({a}, "bc5"), bytes);
    EXPECT_EQ(cache.read(TextureDiskCache::key({b}, "bc5")), bytes);
    TextureDiskCache off(std::nullopt);
    off.write(TextureDiskCache::key({c}, "bc5"), bytes);
    EXPECT_FALSE(off.read(TextureDiskCache::key({c}, "bc5")));
    EXPECT_FALSE(cache.read(TextureDiskCache::key({c}, "bc5")));

    setenv("OBSCURA_TEXTURE_CACHE", "off", 1);
    EXPECT_FALSE(cacheFolderFromEnvironment("OBSCURA_TEXTURE_CACHE"));
    setenv("OBSCURA_TEXTURE_CACHE", dir.c_str(), 1);
    EXPECT_EQ(cacheFolderFromEnvironment("OBSCURA_TEXTURE_CACHE"), dir);
    unsetenv("OBSCURA_TEXTURE_CACHE");
    setenv("XDG_CACHE_HOME", dir.c_str(), 1);
    EXPECT_EQ(cacheFolderFromEnvironment("OBSCURA_TEXTURE_CACHE"), dir / "obscura");
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace obscura::delegate
