// GPU timestamps around each frame-graph pass; read back after the frame's fence.
#pragma once

#include "gpu/device.h"

#include <string>
#include <vector>

namespace obscura::gpu {

struct PassTime {
    std::string pass;
    double milliseconds;
};

class Timestamps {
public:
    explicit Timestamps(Device& device, uint32_t maxPasses = 64);
    ~Timestamps();
    Timestamps(const Timestamps&) = delete;
    Timestamps& operator=(const Timestamps&) = delete;

    void reset(VkCommandBuffer cmd);
    void begin(VkCommandBuffer cmd, const std::string& pass);
    void end(VkCommandBuffer cmd);
    // After the GPU finished the frame.
    std::vector<PassTime> resolve();

private:
    Device& device_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t capacity_;
    std::vector<std::string> names_;
    double periodNs_;
};

}  // namespace obscura::gpu
