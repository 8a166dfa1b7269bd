// Vulkan entry points through tables of the plugin's own, as volk does: the plugin is built with
// VK_NO_PROTOTYPES and does not link the loader, so a host's own Vulkan (its loader, or one linked
// statically, or layers it interposes) never stands in for ours through the dynamic linker. The
// loader is opened by name (libvulkan.so.1) on first use; each instance and each device gets a
// table of its functions (vkGetInstanceProcAddr / vkGetDeviceProcAddr), found again from the
// handle a call is made on by its dispatch key, the loader's dispatch pointer that a device and its
// queues and command buffers share (the same key Vulkan layers use).
//
// Code in namespace obscura calls Vulkan as usual (`vkCmdDraw(cmd, ...)`): the wrappers below are
// what those names resolve to. A function missing from the lists is a compile error, not a call
// into whatever the process happens to export.
#pragma once

#ifndef VK_NO_PROTOTYPES
#error "the plugin's Vulkan code is built with VK_NO_PROTOTYPES (gpu/CMakeLists.txt)"
#endif
#include <vulkan/vulkan.h>

#include <string>
#include <type_traits>

// Functions the loader answers without an instance.
#define OBSCURA_VK_LOADER_FUNCTIONS(X) \
    X(vkCreateInstance)                \
    X(vkEnumerateInstanceLayerProperties) \
    X(vkEnumerateInstanceExtensionProperties)

// Functions dispatched on a VkInstance or VkPhysicalDevice.
#define OBSCURA_VK_INSTANCE_FUNCTIONS(X)                \
    X(vkDestroyInstance)                                \
    X(vkEnumeratePhysicalDevices)                       \
    X(vkEnumerateDeviceExtensionProperties)             \
    X(vkGetPhysicalDeviceExternalSemaphoreProperties)   \
    X(vkGetPhysicalDeviceFeatures)                      \
    X(vkGetPhysicalDeviceFeatures2)                     \
    X(vkGetPhysicalDeviceFormatProperties)              \
    X(vkGetPhysicalDeviceMemoryProperties)              \
    X(vkGetPhysicalDeviceProperties)                    \
    X(vkGetPhysicalDeviceProperties2)                   \
    X(vkGetPhysicalDeviceQueueFamilyProperties)         \
    X(vkCreateDevice)

// Functions dispatched on a VkDevice, VkQueue or VkCommandBuffer (Vulkan 1.3 core). Extension
// functions are fetched where their extension is enabled (vkGetDeviceProcAddr).
#define OBSCURA_VK_DEVICE_FUNCTIONS(X) \
    X(vkGetDeviceProcAddr)             \
    X(vkDestroyDevice)                 \
    X(vkDeviceWaitIdle)                \
    X(vkGetDeviceQueue)                \
    X(vkQueueSubmit)                   \
    X(vkAllocateCommandBuffers)        \
    X(vkFreeCommandBuffers)            \
    X(vkResetCommandBuffer)            \
    X(vkBeginCommandBuffer)            \
    X(vkEndCommandBuffer)              \
    X(vkCreateCommandPool)             \
    X(vkDestroyCommandPool)            \
    X(vkCreateFence)                   \
    X(vkDestroyFence)                  \
    X(vkResetFences)                   \
    X(vkWaitForFences)                 \
    X(vkCreateSemaphore)               \
    X(vkDestroySemaphore)              \
    X(vkAllocateMemory)                \
    X(vkFreeMemory)                    \
    X(vkMapMemory)                     \
    X(vkCreateBuffer)                  \
    X(vkDestroyBuffer)                 \
    X(vkBindBufferMemory)              \
    X(vkGetBufferMemoryRequirements)   \
    X(vkCreateImage)                   \
    X(vkDestroyImage)                  \
    X(vkBindImageMemory)               \
    X(vkGetImageMemoryRequirements)    \
    X(vkGetDeviceImageMemoryRequirements) \
    X(vkCreateImageView)               \
    X(vkDestroyImageView)              \
    X(vkCreateSampler)                 \
    X(vkDestroySampler)                \
    X(vkCreateShaderModule)            \
    X(vkDestroyShaderModule)           \
    X(vkCreateDescriptorSetLayout)     \
    X(vkDestroyDescriptorSetLayout)    \
    X(vkCreateDescriptorPool)          \
    X(vkDestroyDescriptorPool)         \
    X(vkResetDescriptorPool)           \
    X(vkAllocateDescriptorSets)        \
    X(vkUpdateDescriptorSets)          \
    X(vkCreatePipelineLayout)          \
    X(vkDestroyPipelineLayout)         \
    X(vkCreatePipelineCache)           \
    X(vkDestroyPipelineCache)          \
    X(vkGetPipelineCacheData)          \
    X(vkCreateComputePipelines)        \
    X(vkCreateGraphicsPipelines)       \
    X(vkDestroyPipeline)               \
    X(vkCreateQueryPool)               \
    X(vkDestroyQueryPool)              \
    X(vkGetQueryPoolResults)           \
    X(vkCmdBeginRendering)             \
    X(vkCmdEndRendering)               \
    X(vkCmdBindDescriptorSets)         \
    X(vkCmdBindIndexBuffer)            \
    X(vkCmdBindPipeline)               \
    X(vkCmdBindVertexBuffers)          \
    X(vkCmdBlitImage)                  \
    X(vkCmdClearAttachments)           \
    X(vkCmdCopyBuffer)                 \
    X(vkCmdCopyBufferToImage)          \
    X(vkCmdCopyImageToBuffer)          \
    X(vkCmdDispatch)                   \
    X(vkCmdDraw)                       \
    X(vkCmdDrawIndexed)                \
    X(vkCmdDrawIndexedIndirect)        \
    X(vkCmdFillBuffer)                 \
    X(vkCmdPipelineBarrier2)           \
    X(vkCmdPushConstants)              \
    X(vkCmdResetQueryPool)             \
    X(vkCmdSetScissor)                 \
    X(vkCmdSetStencilWriteMask)        \
    X(vkCmdSetViewport)                \
    X(vkCmdWriteTimestamp2)

namespace obscura::gpu::vk {

#define OBSCURA_VK_MEMBER(name) PFN_##name name = nullptr;
struct LoaderTable {
    PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
    OBSCURA_VK_LOADER_FUNCTIONS(OBSCURA_VK_MEMBER)
};
struct InstanceTable {
    OBSCURA_VK_INSTANCE_FUNCTIONS(OBSCURA_VK_MEMBER)
};
struct DeviceTable {
    OBSCURA_VK_DEVICE_FUNCTIONS(OBSCURA_VK_MEMBER)
};
#undef OBSCURA_VK_MEMBER

// The table a pointer to member belongs to.
template <auto Member>
struct MemberOf;
template <typename T, typename F, F T::*Member>
struct MemberOf<Member> {
    using Table = T;
};

// Opens the loader once per process; the reason when it cannot (no libvulkan.so.1, or one without
// vkGetInstanceProcAddr), empty when it is there.
std::string openLoader();
// The loader's functions; openLoader() must have succeeded.
const LoaderTable& loader();

// The dispatch key of a dispatchable handle (VkInstance, VkPhysicalDevice, VkDevice, VkQueue,
// VkCommandBuffer): the dispatch table pointer the loader keeps in the object's first word.
inline const void* dispatchKey(const void* handle) { return *static_cast<const void* const*>(handle); }

// Tables are filled right after an instance or device is created and dropped right after it is
// destroyed (by the key taken before). Any thread may call through them meanwhile.
void addInstance(VkInstance instance);
void addDevice(VkInstance instance, VkDevice device);
void forget(const void* key);

// The table of the instance or device `handle` belongs to; a handle of neither is a logic_error.
const InstanceTable& instanceTable(const void* handle);
const DeviceTable& deviceTable(const void* handle);

}  // namespace obscura::gpu::vk

namespace obscura {

namespace gpu::vk {
// A Vulkan function as the plugin calls it: its exact parameters (so arguments convert at the call,
// as with the prototypes), dispatched through the table its first argument's instance or device
// was given (Loader: the loader's table).
template <auto Member, typename Function>
struct Call;
template <auto Member, typename R, typename Handle, typename... Params>
struct Call<Member, R (*)(Handle, Params...)> {
    R operator()(Handle handle, Params... params) const {
        if constexpr (std::is_same_v<typename MemberOf<Member>::Table, DeviceTable>)
            return (deviceTable(handle).*Member)(handle, params...);
        else if constexpr (std::is_same_v<typename MemberOf<Member>::Table, InstanceTable>)
            return (instanceTable(handle).*Member)(handle, params...);
        else
            return (loader().*Member)(handle, params...);
    }
};
}  // namespace gpu::vk

// What `vkX(...)` names inside the plugin.
#define OBSCURA_VK_LOADER_CALL(name) \
    inline constexpr gpu::vk::Call<&gpu::vk::LoaderTable::name, PFN_##name> name{};
#define OBSCURA_VK_INSTANCE_CALL(name) \
    inline constexpr gpu::vk::Call<&gpu::vk::InstanceTable::name, PFN_##name> name{};
#define OBSCURA_VK_DEVICE_CALL(name) \
    inline constexpr gpu::vk::Call<&gpu::vk::DeviceTable::name, PFN_##name> name{};
OBSCURA_VK_LOADER_CALL(vkGetInstanceProcAddr)
OBSCURA_VK_LOADER_FUNCTIONS(OBSCURA_VK_LOADER_CALL)
OBSCURA_VK_INSTANCE_FUNCTIONS(OBSCURA_VK_INSTANCE_CALL)
OBSCURA_VK_DEVICE_FUNCTIONS(OBSCURA_VK_DEVICE_CALL)
#undef OBSCURA_VK_LOADER_CALL
#undef OBSCURA_VK_INSTANCE_CALL
#undef OBSCURA_VK_DEVICE_CALL

}  // namespace obscura
