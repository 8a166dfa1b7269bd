// Pipelines are compiled once per device and found again by name. A pass names each pipeline it
// binds and says how to build it: declared with the pass (FrameGraph::PassBuilder::usesPipeline),
// the frame's missing pipelines are built together before it records, several at a time; asked
// for only as the pass records, a pipeline is built there, alone.
#pragma once

#include "gpu/pipeline.h"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace obscura::gpu {

class PipelineCache {
public:
    // A pipeline a pass binds: its name in the cache and how to build it.
    struct Request {
        std::string key;
        std::function<std::unique_ptr<Pipeline>(Device&)> build;
    };
    template <typename Desc>
    static Request request(std::string key, std::function<Desc()> describe) {
        return {std::move(key), [describe = std::move(describe)](Device& device) {
                    return std::make_unique<Pipeline>(device, describe());
                }};
    }

    explicit PipelineCache(Device& device) : device_(device) {}

    // Builds the pipelines of `requests` the cache lacks, on as many threads as the machine has
    // cores (vkCreate*Pipelines may run concurrently; each pipeline makes its own layouts and
    // modules): a driver compiling the frame's shaders for the first time does it in parallel.
    // Messages logged meanwhile reach the log on this thread, afterwards (Context::HeldLog). A
    // failure is thrown once every build has ended; the pipelines built are kept.
    void prepare(const std::vector<const Request*>& requests);

    // The pipeline of `request`, built now if no prepare() built it.
    const Pipeline& get(const Request& request);
    bool contains(const std::string& key) const { return pipelines_.contains(key); }
    Device& device() { return device_; }

private:
    Device& device_;
    std::map<std::string, std::unique_ptr<Pipeline>> pipelines_;
};

}  // namespace obscura::gpu
