// The driver's compiled pipelines kept on disk between processes (a VkPipelineCache), so that a
// process after the first skips compiling shaders to the device's code: start-up of a still is
// mostly device creation and pipeline compilation. One file per device and driver build (vendor,
// device and the driver's pipelineCacheUUID in its name), written when the device is destroyed,
// to a temporary name then renamed, so that concurrent processes never read half a file; the last
// one to finish wins. The file's own header (size and hash of the data) and the data's Vulkan
// header are checked before the driver sees them: a truncated, corrupt or foreign file is ignored
// (the cache only saves time), since not every driver survives bad initial data.
#pragma once

#include "gpu/vulkan_functions.h"

#include <filesystem>
#include <optional>

namespace obscura::gpu {

class Context;

class PipelineDiskCache {
public:
    // `folder` nullopt: a cache in memory only (nothing read or written).
    PipelineDiskCache(const Context& context, std::optional<std::filesystem::path> folder);
    ~PipelineDiskCache();
    PipelineDiskCache(const PipelineDiskCache&) = delete;
    PipelineDiskCache& operator=(const PipelineDiskCache&) = delete;

    VkPipelineCache vk() const { return cache_; }
    // The file this device's pipelines are kept in (nullopt when off).
    const std::optional<std::filesystem::path>& file() const { return file_; }
    // Writes the cache's data to its file if it holds more than was read.
    void save();

private:
    VkDevice device_;
    VkPipelineCache cache_ = VK_NULL_HANDLE;
    std::optional<std::filesystem::path> file_;
    size_t loadedBytes_ = 0;
};

}  // namespace obscura::gpu
