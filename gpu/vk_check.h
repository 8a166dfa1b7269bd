// Vulkan call checking: an unexpected VkResult is a device failure carried as an exception
// inside the plugin (caught at the ABI boundary and turned into OBSCURA_ERROR_DEVICE).
#pragma once

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace obscura::gpu {

struct DeviceError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

const char* vkResultName(VkResult r);

inline void vkCheck(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw DeviceError(std::string(what) + " failed: " + vkResultName(r));
}

}  // namespace obscura::gpu
