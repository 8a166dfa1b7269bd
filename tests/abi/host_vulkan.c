/* A host with a Vulkan of its own, as a DCC that links a loader statically or wraps Vulkan's entry
 * points exports them: Vulkan's names, defined by the executable and exported to every library it
 * loads. The plugin must call the loader it opens itself (gpu/vulkan_functions.h), never these:
 * linked into abi_c_host, any call that reaches one ends the process with the function's name. */
#include <stdio.h>
#include <stdlib.h>

#define HOST_VULKAN_FUNCTION(name)                                               \
    void name(void);                                                             \
    void name(void) {                                                            \
        fprintf(stderr, "FAILED: the plugin called the host's %s\n", #name);     \
        abort();                                                                 \
    }

HOST_VULKAN_FUNCTION(vkGetInstanceProcAddr)
HOST_VULKAN_FUNCTION(vkCreateInstance)
HOST_VULKAN_FUNCTION(vkEnumerateInstanceLayerProperties)
HOST_VULKAN_FUNCTION(vkEnumeratePhysicalDevices)
HOST_VULKAN_FUNCTION(vkCreateDevice)
HOST_VULKAN_FUNCTION(vkGetDeviceProcAddr)
HOST_VULKAN_FUNCTION(vkGetDeviceQueue)
HOST_VULKAN_FUNCTION(vkQueueSubmit)
HOST_VULKAN_FUNCTION(vkAllocateMemory)
HOST_VULKAN_FUNCTION(vkCreateImage)
HOST_VULKAN_FUNCTION(vkCmdDraw)
HOST_VULKAN_FUNCTION(vkCmdDispatch)
HOST_VULKAN_FUNCTION(vkCmdPipelineBarrier2)
HOST_VULKAN_FUNCTION(vkDestroyDevice)
