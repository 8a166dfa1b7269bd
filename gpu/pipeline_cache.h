// Pipelines are compiled once per device and found again by name; a pass names its pipeline and
// says how to build it the first time, when it records.
#pragma once

#include "gpu/pipeline.h"

#include <functional>
#include <map>
#include <memory>
#include <string>

namespace obscura::gpu {

class PipelineCache {
public:
    explicit PipelineCache(Device& device) : device_(device) {}

    template <typename Desc>
    const Pipeline& get(const std::string& key, const std::function<Desc()>& describe) {
        auto it = pipelines_.find(key);
        if (it != pipelines_.end()) return *it->second;
        auto pipeline = std::make_unique<Pipeline>(device_, describe());
        return *pipelines_.emplace(key, std::move(pipeline)).first->second;
    }
    Device& device() { return device_; }

private:
    Device& device_;
    std::map<std::string, std::unique_ptr<Pipeline>> pipelines_;
};

}  // namespace obscura::gpu
