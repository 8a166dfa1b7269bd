// What the driver compiled each pipeline into (VK_KHR_pipeline_executable_properties): register
// counts, code size and the like, by the driver's own names. A shader edit can cost a GPU more
// through the registers it takes (fewer workgroups in flight) than through its work; these numbers
// show it. Captured only where OBSCURA_PIPELINE_STATISTICS is set (capture may bypass the
// driver's caches) and the device has the extension; logged at info level as each pipeline is made.
#pragma once

#include "gpu/vulkan_functions.h"

#include <string>

namespace obscura::gpu {

class Context;

// Whether this process asks for the statistics (the environment variable).
bool pipelineStatisticsRequested();

// Logs one line per executable of `pipeline` (a shader stage, or the driver's split of it), named
// after `shader`. Nothing where the context does not capture them.
void logPipelineStatistics(const Context& context, VkPipeline pipeline, const std::string& shader);

}  // namespace obscura::gpu
