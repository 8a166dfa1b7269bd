// The Vulkan instance, the chosen physical device, the logical device and its one queue.
// Each delegate owns one Context: delegates in one process are fully independent.
#pragma once

#include "gpu/fault_injection.h"
#include "gpu/log.h"
#include "gpu/result.h"

#include "gpu/vulkan_functions.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace obscura::gpu {

struct ContextOptions {
    std::string deviceSelector;  // name substring or index; empty: OBSCURA_DEVICE, then the best device
    bool validation = false;     // Khronos validation layer; its errors are counted
    LogSink log;
    FaultInjection faults;
};

// What the device can share with another VkDevice (or a GL context) of the same GPU: memory and
// timeline semaphores as opaque file descriptors (the ABI's display interop).
struct ExternalHandleSupport {
    bool memoryFd = false;     // VK_KHR_external_memory_fd, enabled
    bool semaphoreFd = false;  // VK_KHR_external_semaphore_fd with exportable timeline semaphores, enabled
    uint8_t deviceUUID[VK_UUID_SIZE] = {};
    uint8_t driverUUID[VK_UUID_SIZE] = {};
};

// VK_KHR_pipeline_executable_properties' queries, where the context captures pipeline statistics
// (gpu/pipeline_statistics.h); null otherwise.
struct PipelineExecutableFunctions {
    PFN_vkGetPipelineExecutablePropertiesKHR properties = nullptr;
    PFN_vkGetPipelineExecutableStatisticsKHR statistics = nullptr;
};

struct PhysicalDeviceSummary {
    std::string name;
    std::string driver;
    uint32_t apiVersion = 0;
    bool discrete = false;
    bool cpu = false;
    VkSampleCountFlags msaaSamples = 0;
};

class Context {
public:
    static Result<std::unique_ptr<Context>> create(const ContextOptions& options);
    // Devices as `obscura info` lists them (own short-lived instance, no validation).
    static Result<std::vector<PhysicalDeviceSummary>> enumerate();
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    const ExternalHandleSupport& externalHandles() const { return externalHandles_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    // The core features the device was created with (each one the passes use, where supported).
    const VkPhysicalDeviceFeatures& enabledFeatures() const { return enabledFeatures_; }
    // VK_KHR_push_descriptor, which every device Obscura picks has.
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet() const { return cmdPushDescriptorSet_; }
    const PipelineExecutableFunctions& pipelineExecutableFunctions() const { return pipelineExecutables_; }
    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }
    const PhysicalDeviceSummary& summary() const { return summary_; }
    bool validationEnabled() const { return messenger_ != VK_NULL_HANDLE; }

    // Validation messages of error severity since creation.
    uint32_t validationErrorCount() const { return validationErrors_.load(); }
    void log(LogLevel level, const std::string& message) const;
    // While one lives, messages logged on any thread wait and are logged, in order, on the thread
    // that ends it: work spread over threads of the plugin's own (PipelineCache::prepare) reports
    // to the host's log callback on the thread that called into the plugin.
    class HeldLog {
    public:
        explicit HeldLog(const Context& context);
        ~HeldLog();
        HeldLog(const HeldLog&) = delete;
        HeldLog& operator=(const HeldLog&) = delete;

    private:
        const Context& context_;
    };

    // Records and runs a command buffer to completion (frames, uploads at sync time). Not re-entrant.
    template <typename F>
    void submitAndWait(F&& record);

    // Simulated failures (gpu/fault_injection.h); the delegate counts its renders into it.
    FaultInjection& faults() { return faults_; }

    VkCommandPool commandPool() const { return commandPool_; }
    VkFence fence() const { return fence_; }

private:
    Context() = default;
    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                        VkDebugUtilsMessageTypeFlagsEXT types,
                                                        const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                        void* user);
    void beginOneShot(VkCommandBuffer& cmd);
    void endOneShot(VkCommandBuffer cmd);

    LogSink log_;
    FaultInjection faults_;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceFeatures enabledFeatures_{};
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet_ = nullptr;
    PipelineExecutableFunctions pipelineExecutables_;
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    PhysicalDeviceSummary summary_;
    ExternalHandleSupport externalHandles_;
    VkCommandPool commandPool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkCommandBuffer oneShot_ = VK_NULL_HANDLE;  // reused by every submitAndWait
    bool recording_ = false;
    std::atomic<uint32_t> validationErrors_{0};
    mutable std::mutex heldMutex_;
    mutable int holders_ = 0;  // HeldLog objects alive
    mutable std::vector<std::pair<LogLevel, std::string>> heldMessages_;
};

template <typename F>
void Context::submitAndWait(F&& record) {
    if (recording_) throw std::logic_error("submitAndWait called while recording another submission");
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    beginOneShot(cmd);
    recording_ = true;
    try {
        record(cmd);
    } catch (...) {
        recording_ = false;
        throw;
    }
    recording_ = false;
    endOneShot(cmd);
}

}  // namespace obscura::gpu
