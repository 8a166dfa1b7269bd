// Files the disk caches share between writers (gpu/replace_file.h): however many threads replace
// one file at once, a reader finds one writer's bytes whole, and no temporary file is left.
#include "gpu/replace_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace obscura::gpu {
namespace {

TEST(ReplaceFile, ConcurrentWritersOfOneFileLeaveOneWholeVersion) {
    const auto folder = std::filesystem::temp_directory_path() / ("obscura-replace-" + std::to_string(getpid()));
    std::filesystem::remove_all(folder);
    const auto file = folder / "shared.bin";
    constexpr int kThreads = 8, kWrites = 50;
    constexpr size_t kBytes = 1 << 16;
    std::vector<std::thread> writers;
    std::vector<int> failures(kThreads, 0);
    for (int t = 0; t < kThreads; ++t)
        writers.emplace_back([&, t] {
            const std::vector<char> bytes(kBytes, char('a' + t));
            for (int i = 0; i < kWrites; ++i) failures[size_t(t)] += replaceFile(file, bytes.data(), bytes.size()) ? 0 : 1;
        });
    for (std::thread& writer : writers) writer.join();

    for (int t = 0; t < kThreads; ++t) EXPECT_EQ(failures[size_t(t)], 0) << "writer " << t;
    const std::optional<std::vector<char>> read = readWholeFile(file);
    ASSERT_TRUE(read);
    ASSERT_EQ(read->size(), kBytes);
    for (char c : *read) ASSERT_EQ(c, read->front()) << "one writer's bytes, whole";
    size_t entries = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder)) ++entries;
    EXPECT_EQ(entries, 1u) << "no temporary file left";
    std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace obscura::gpu
