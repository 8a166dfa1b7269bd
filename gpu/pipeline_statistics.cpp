#include "gpu/pipeline_statistics.h"

#include "gpu/context.h"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace obscura::gpu {

bool pipelineStatisticsRequested() { return std::getenv("OBSCURA_PIPELINE_STATISTICS") != nullptr; }

namespace {

std::string statisticValue(const VkPipelineExecutableStatisticKHR& s) {
    char text[64];
    switch (s.format) {
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: return s.value.b32 ? "yes" : "no";
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
            std::snprintf(text, sizeof text, "%" PRId64, s.value.i64);
            break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
            std::snprintf(text, sizeof text, "%" PRIu64, s.value.u64);
            break;
        default: std::snprintf(text, sizeof text, "%g", s.value.f64); break;
    }
    return text;
}

}  // namespace

void logPipelineStatistics(const Context& context, VkPipeline pipeline, const std::string& shader) {
    const PipelineExecutableFunctions& f = context.pipelineExecutableFunctions();
    if (!f.properties || !f.statistics) return;
    VkPipelineInfoKHR info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
    info.pipeline = pipeline;
    uint32_t count = 0;
    if (f.properties(context.device(), &info, &count, nullptr) != VK_SUCCESS) return;
    std::vector<VkPipelineExecutablePropertiesKHR> executables(count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR});
    if (f.properties(context.device(), &info, &count, executables.data()) != VK_SUCCESS) return;
    for (uint32_t e = 0; e < count; ++e) {
        VkPipelineExecutableInfoKHR which{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
        which.pipeline = pipeline;
        which.executableIndex = e;
        uint32_t statisticCount = 0;
        if (f.statistics(context.device(), &which, &statisticCount, nullptr) != VK_SUCCESS) continue;
        std::vector<VkPipelineExecutableStatisticKHR> statistics(statisticCount,
                                                                 {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
        if (f.statistics(context.device(), &which, &statisticCount, statistics.data()) != VK_SUCCESS) continue;
        std::string line = "pipeline statistics: " + shader + " [" + executables[e].name + "]";
        for (const auto& s : statistics) line += std::string(", ") + s.name + " " + statisticValue(s);
        context.log(LogLevel::Info, line);
    }
}

}  // namespace obscura::gpu
