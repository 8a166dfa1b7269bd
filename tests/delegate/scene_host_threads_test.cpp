// The harness's scene host under the delegate's parallel rprim sync: it declares its callbacks
// thread-safe (OBSCURA_SCENE_DELEGATE_THREAD_SAFE), so what it returns must stay valid on each
// thread until that thread's next callback (include/obscura/obscura.h, ObscuraValue's lifetime).
#include "harness/usd_scene_host.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <string>
#include <thread>
#include <vector>

namespace obscura::test {
namespace {

TEST(SceneHostThreads, WhatEachThreadIsReturnedStaysItsOwnUntilItsNextCallback) {
    auto opened = usda::Stage::openFromString(R"(#usda 1.0
def Mesh "A"
{
    point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    int[] faceVertexCounts = [4]
    int[] faceVertexIndices = [0, 1, 2, 3]
}
def Mesh "B"
{
    point3f[] points = [(5, 6, 7), (8, 9, 10), (11, 12, 13)]
    int[] faceVertexCounts = [3]
    int[] faceVertexIndices = [0, 1, 2]
}
)",
                                              "threads.usda");
    ASSERT_TRUE(std::holds_alternative<std::unique_ptr<usda::Stage>>(opened));
    harness::UsdSceneHost host(*std::get<std::unique_ptr<usda::Stage>>(opened));
    const ObscuraSceneDelegate& d = host.sceneDelegate();
    EXPECT_NE(d.flags & OBSCURA_SCENE_DELEGATE_THREAD_SAFE, 0u);

    std::atomic<int> wrong{0};
    auto pull = [&](const char* path, std::vector<float> expected) {
        for (int i = 0; i < 2000; ++i) {
            ObscuraValue value{};
            if (d.getValue(d.userData, path, "points", 0.0, &value) != OBSCURA_OK) {
                ++wrong;
                continue;
            }
            // The other thread's callbacks run meanwhile; what this one holds must not change.
            std::this_thread::yield();
            const auto* floats = static_cast<const float*>(value.data);
            if (value.type != OBSCURA_VALUE_FLOAT3 || value.count * 3 != expected.size() ||
                !std::equal(expected.begin(), expected.end(), floats))
                ++wrong;
        }
    };
    std::thread a(pull, "/A", std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    std::thread b(pull, "/B", std::vector<float>{5, 6, 7, 8, 9, 10, 11, 12, 13});
    a.join();
    b.join();
    EXPECT_EQ(wrong.load(), 0);
}

}  // namespace
}  // namespace obscura::test
