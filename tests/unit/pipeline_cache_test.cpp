// PipelineCache::prepare on lavapipe: the pipelines a frame declares are built once each, on as
// many threads as the machine has cores, a failure is reported after the others are kept, and
// what the builds log reaches the log on the calling thread. Validation on, no error allowed.
#include "gpu/pipeline_cache.h"

#include "gpu/vk_check.h"
#include "tests/unit/validated_device_test.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace obscura::gpu {
namespace {

// A compute pipeline of the test's one shader (accumulate_resolve.comp, registered for this test
// under its own name); `variant` tells pipelines apart through a specialization constant the
// shader does not declare.
PipelineCache::Request resolvePipeline(uint32_t variant) {
    return PipelineCache::request<ComputePipelineDesc>(
        "test_resolve." + std::to_string(variant), [variant] {
            return ComputePipelineDesc{"pipeline_cache_test.comp",
                                       {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                       0,
                                       {{7, variant}}};
        });
}

std::vector<const PipelineCache::Request*> pointersTo(const std::vector<PipelineCache::Request>& requests) {
    std::vector<const PipelineCache::Request*> pointers;
    for (const auto& r : requests) pointers.push_back(&r);
    return pointers;
}

class PipelineCachePrepare : public ValidatedDeviceTest {};

TEST_F(PipelineCachePrepare, BuildsEachMissingPipelineOnce) {
    PipelineCache cache(*device_);
    std::atomic<int> builds{0};
    std::vector<PipelineCache::Request> requests;
    for (uint32_t v : {0u, 1u, 2u, 1u, 3u, 0u}) {
        PipelineCache::Request r = resolvePipeline(v);
        r.build = [inner = r.build, &builds](Device& device) {
            ++builds;
            return inner(device);
        };
        requests.push_back(std::move(r));
    }
    cache.prepare(pointersTo(requests));
    EXPECT_EQ(builds.load(), 4);
    for (uint32_t v = 0; v < 4; ++v) EXPECT_TRUE(cache.contains("test_resolve." + std::to_string(v)));
    const Pipeline& first = cache.get(requests[0]);
    EXPECT_NE(first.vk(), VkPipeline(VK_NULL_HANDLE));
    cache.prepare(pointersTo(requests));
    EXPECT_EQ(&cache.get(requests[5]), &first);
    EXPECT_EQ(builds.load(), 4);
}

TEST_F(PipelineCachePrepare, BuildsOnAsManyThreadsAsTheMachineHasCores) {
    PipelineCache cache(*device_);
    const size_t count = 8;
    const size_t expected = std::min<size_t>(count, std::max(1u, std::thread::hardware_concurrency()));
    // Each build waits (up to a time limit) until `expected` builds have started: builds made one
    // after another on a single thread would each wait out the limit and meet one thread id.
    std::mutex mutex;
    std::condition_variable started;
    std::set<std::thread::id> threads;
    size_t running = 0;
    std::vector<PipelineCache::Request> requests;
    for (uint32_t v = 0; v < count; ++v) {
        PipelineCache::Request r = resolvePipeline(v);
        r.build = [inner = r.build, &mutex, &started, &threads, &running, expected](Device& device) {
            {
                std::unique_lock lock(mutex);
                threads.insert(std::this_thread::get_id());
                ++running;
                started.notify_all();
                started.wait_for(lock, std::chrono::seconds(2), [&] { return running >= expected; });
            }
            return inner(device);
        };
        requests.push_back(std::move(r));
    }
    cache.prepare(pointersTo(requests));
    EXPECT_EQ(threads.size(), expected);
    EXPECT_TRUE(threads.contains(std::this_thread::get_id()));
    for (uint32_t v = 0; v < count; ++v) EXPECT_TRUE(cache.contains("test_resolve." + std::to_string(v)));
}

TEST_F(PipelineCachePrepare, AFailureIsThrownOnceTheOtherPipelinesAreKept) {
    PipelineCache cache(*device_);
    std::vector<PipelineCache::Request> requests{resolvePipeline(0), resolvePipeline(1), resolvePipeline(2)};
    requests[1].build = [](Device&) -> std::unique_ptr<Pipeline> { throw DeviceError("no such pipeline"); };
    EXPECT_THROW(cache.prepare(pointersTo(requests)), DeviceError);
    EXPECT_TRUE(cache.contains("test_resolve.0"));
    EXPECT_FALSE(cache.contains("test_resolve.1"));
    EXPECT_TRUE(cache.contains("test_resolve.2"));
}

TEST(PipelineCachePrepareLog, MessagesOfTheBuildsReachTheLogInOrderOnTheCallingThread) {
    struct Message {
        std::string text;
        std::thread::id thread;
    };
    std::vector<Message> messages;  // written by the log alone, which must run on this thread
    ContextOptions options;
    options.validation = true;
    options.log = [&messages](LogLevel, const std::string& text) {
        messages.push_back({text, std::this_thread::get_id()});
    };
    auto context = Context::create(options);
    ASSERT_TRUE(context.ok()) << context.error();
    Device device(std::move(*context));
    PipelineCache cache(device);
    std::vector<PipelineCache::Request> requests;
    for (uint32_t v = 0; v < 4; ++v) {
        PipelineCache::Request r = resolvePipeline(v);
        r.build = [inner = r.build, v](Device& d) {
            d.context().log(LogLevel::Info, "building " + std::to_string(v) + " first part");
            auto pipeline = inner(d);
            d.context().log(LogLevel::Info, "building " + std::to_string(v) + " second part");
            return pipeline;
        };
        requests.push_back(std::move(r));
    }
    const size_t before = messages.size();
    cache.prepare(pointersTo(requests));
    ASSERT_EQ(messages.size(), before + 8);
    std::vector<size_t> firstParts(4), secondParts(4);
    for (size_t i = before; i < messages.size(); ++i) {
        EXPECT_EQ(messages[i].thread, std::this_thread::get_id()) << messages[i].text;
        const uint32_t v = uint32_t(messages[i].text[9] - '0');
        (messages[i].text.ends_with("first part") ? firstParts : secondParts)[v] = i;
    }
    for (uint32_t v = 0; v < 4; ++v) EXPECT_LT(firstParts[v], secondParts[v]) << "pipeline " << v;
    device.context().log(LogLevel::Info, "after");
    EXPECT_EQ(messages.back().text, "after");
    EXPECT_EQ(device.context().validationErrorCount(), 0u);
}

}  // namespace
}  // namespace obscura::gpu
