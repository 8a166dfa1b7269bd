// Compiled pipelines kept on disk between delegates (gpu/pipeline_disk_cache.h): a delegate writes
// its device's file when it is destroyed, the next one reads it, and a file that is truncated,
// corrupt or written for another device is ignored with a note while the frame renders as ever.
#include "tests/delegate/render_fixture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace obscura::test {
namespace {

namespace fs = std::filesystem;

// The cache folder of this test alone, made empty, named to every delegate created while it lives.
class CacheFolder {
public:
    CacheFolder() : path_(fs::temp_directory_path() / ("obscura-pipeline-cache-" + std::to_string(getpid()))) {
        fs::remove_all(path_);
        const char* previous = std::getenv("OBSCURA_PIPELINE_CACHE");
        if (previous) previous_ = previous;
        setenv("OBSCURA_PIPELINE_CACHE", path_.c_str(), 1);
    }
    ~CacheFolder() {
        if (previous_.empty()) unsetenv("OBSCURA_PIPELINE_CACHE");
        else setenv("OBSCURA_PIPELINE_CACHE", previous_.c_str(), 1);
        fs::remove_all(path_);
    }
    std::vector<fs::path> files() const {
        std::vector<fs::path> found;
        if (fs::exists(path_))
            for (const auto& entry : fs::directory_iterator(path_)) found.push_back(entry.path());
        return found;
    }

private:
    fs::path path_;
    std::string previous_;
};

std::vector<char> readAll(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeAll(const fs::path& file, const std::vector<char>& bytes) {
    std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// Renders the lit plane with a new delegate, destroys it, and returns its notes about the cache
// and the centre pixel's red radiance.
struct CacheRun {
    std::vector<std::string> notes;
    float centre = 0.0f;
};
CacheRun renderOnce() {
    LitPlaneScene scene;
    scene.host.addPrim("distantLight", "/Sun", {{"inputs:intensity", HostValue::floatValue(1.0f)}},
                       lightPointingAlong({0.0, 0.0, -1.0}));
    CacheRun run;
    const std::vector<float> color = scene.renderColor();
    run.centre = color[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 4];
    EXPECT_EQ(scene.host.destroyDelegate(), OBSCURA_OK);
    for (const std::string& note : scene.host.loggedInfos())
        if (note.find("pipeline cache") != std::string::npos) run.notes.push_back(note);
    return run;
}

constexpr size_t kFileHeaderBytes = 24;  // magic, data size, data hash
// VkPipelineCacheHeaderVersionOne: size, version (1), vendor, device, the driver's cache UUID.
constexpr size_t kVulkanHeaderBytes = 32;

// The FNV-1a hash the file's header holds (gpu/content_hash.h).
uint64_t fnv1a(const char* data, size_t size) {
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < size; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
    return h;
}

TEST(PipelineDiskCache, ADelegateWritesItsDevicesFileAndTheNextReadsIt) {
    CacheFolder folder;
    const CacheRun first = renderOnce();
    EXPECT_TRUE(first.notes.empty()) << first.notes.front();
    const std::vector<fs::path> files = folder.files();
    ASSERT_EQ(files.size(), 1u) << "one file per device, nothing left behind";
    EXPECT_EQ(files[0].extension(), ".bin");
    EXPECT_EQ(files[0].filename().string().rfind("pipelines-", 0), 0u) << files[0];
    const std::vector<char> bytes = readAll(files[0]);
    ASSERT_GE(bytes.size(), kFileHeaderBytes + kVulkanHeaderBytes);
    EXPECT_EQ(std::string(bytes.data(), 8), "OBSCPLC1");
    uint32_t headerVersion = 0;
    std::memcpy(&headerVersion, bytes.data() + kFileHeaderBytes + 4, sizeof(headerVersion));
    EXPECT_EQ(headerVersion, 1u) << "the driver's data, VK_PIPELINE_CACHE_HEADER_VERSION_ONE";

    const CacheRun second = renderOnce();
    EXPECT_TRUE(second.notes.empty()) << second.notes.front();
    EXPECT_EQ(second.centre, first.centre);
    EXPECT_EQ(folder.files().size(), 1u);
}

TEST(PipelineDiskCache, ABadFileIsIgnoredWithANoteAndRewritten) {
    CacheFolder folder;
    const CacheRun first = renderOnce();
    ASSERT_EQ(folder.files().size(), 1u);
    const fs::path file = folder.files()[0];
    const std::vector<char> good = readAll(file);

    struct Case {
        const char* why;
        std::vector<char> bytes;
    };
    std::vector<char> truncated(good.begin(), good.end() - 1);
    std::vector<char> corrupt = good;
    corrupt[kFileHeaderBytes + 1] ^= 0x5a;
    std::vector<char> foreign = good;  // another vendor's data, its hash made whole again
    foreign[kFileHeaderBytes + 8] ^= 0x01;
    const uint64_t hash = fnv1a(foreign.data() + kFileHeaderBytes, foreign.size() - kFileHeaderBytes);
    std::memcpy(foreign.data() + 16, &hash, sizeof(hash));
    std::vector<char> stranger(good.size(), 'x');
    const std::vector<Case> cases = {{"truncated", truncated},
                                     {"corrupt", corrupt},
                                     {"written by another device or driver", foreign},
                                     {"not a pipeline cache of this renderer", stranger},
                                     {"shorter than its header", {'O', 'B'}}};
    for (const Case& c : cases) {
        writeAll(file, c.bytes);
        const CacheRun run = renderOnce();
        ASSERT_EQ(run.notes.size(), 1u) << c.why;
        EXPECT_NE(run.notes[0].find(c.why), std::string::npos) << run.notes[0];
        EXPECT_NE(run.notes[0].find(file.filename().string()), std::string::npos) << run.notes[0];
        EXPECT_EQ(run.centre, first.centre) << c.why;
        EXPECT_EQ(std::string(readAll(file).data(), 8), "OBSCPLC1") << c.why << ": written again, whole";
    }
}

TEST(PipelineDiskCache, OffWritesNothing) {
    CacheFolder folder;
    setenv("OBSCURA_PIPELINE_CACHE", "off", 1);
    renderOnce();
    EXPECT_TRUE(folder.files().empty());
}

}  // namespace
}  // namespace obscura::test
