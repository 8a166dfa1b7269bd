// Pipelines are compiled once per delegate and found again by name; a pass names its pipeline
// and says how to build it the first time.
#pragma once

#include "gpu/pipeline.h"

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace obscura::passes {

class PipelineCache {
public:
    explicit PipelineCache(gpu::Device& device) : device_(device) {}

    template <typename Desc>
    const gpu::Pipeline& get(const std::string& key, const std::function<Desc()>& describe) {
        auto it = pipelines_.find(key);
        if (it != pipelines_.end()) return *it->second;
        auto pipeline = std::make_unique<gpu::Pipeline>(device_, describe());
        return *pipelines_.emplace(key, std::move(pipeline)).first->second;
    }
    gpu::Device& device() { return device_; }

private:
    gpu::Device& device_;
    std::map<std::string, std::unique_ptr<gpu::Pipeline>> pipelines_;
};

}  // namespace obscura::passes
