// Vulkan call checking: an unexpected VkResult is a device failure carried as an exception
// inside the plugin (caught at the ABI boundary and turned into OBSCURA_ERROR_OUT_OF_MEMORY for
// the out-of-memory results, OBSCURA_ERROR_DEVICE for the others).
#pragma once

#include "gpu/vulkan_functions.h"

#include <stdexcept>
#include <string>

namespace obscura::gpu {

struct DeviceError : std::runtime_error {
    explicit DeviceError(const std::string& message, VkResult vkResult = VK_ERROR_UNKNOWN)
        : std::runtime_error(message), result(vkResult) {}
    VkResult result;
    bool outOfMemory() const {
        return result == VK_ERROR_OUT_OF_HOST_MEMORY || result == VK_ERROR_OUT_OF_DEVICE_MEMORY;
    }
    bool deviceLost() const { return result == VK_ERROR_DEVICE_LOST; }
};

const char* vkResultName(VkResult r);

inline void vkCheck(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw DeviceError(std::string(what) + " failed: " + vkResultName(r), r);
}

}  // namespace obscura::gpu
