// The viewer's own Vulkan device, on the GPU the plugin renders with, and what it shows render
// buffers with: a render buffer's pixels in a buffer of this device (imported from the plugin's
// exported memory, ABI 1.2, or uploaded from a mapped buffer), turned into an RGBA8 image by
// aov_display.comp. A host of the ABI: it shares memory with the plugin, never its objects.
#pragma once

#include <obscura/obscura.h>

#include <vulkan/vulkan.h>

#include <functional>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace obscura::harness::view {

// Throws std::runtime_error naming `what` unless `result` is VK_SUCCESS.
void check(VkResult result, const char* what);

// A pipeline barrier on a colour image's single mip and layer.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags srcAccess,
                  VkAccessFlags dstAccess, VkPipelineStageFlags srcStage, VkPipelineStageFlags dstStage);

// How an AOV is shown (aov_display.comp).
enum class AovView : uint32_t { Display = 0, Depth = 1, Normal = 2, Motion = 3, PrimId = 4 };

struct DisplayDeviceOptions {
    bool validation = false;                     // Khronos validation; errors are counted
    std::vector<std::string> instanceExtensions;  // a window system's surface extensions
    bool swapchain = false;                      // enable VK_KHR_swapchain
    std::string deviceName;                      // the plugin's device (ObscuraRenderStats::deviceName)
    const uint8_t* deviceUUID = nullptr;         // or its UUID (ObscuraExternalBuffer), which wins
};

class DisplayDevice {
public:
    static std::variant<std::unique_ptr<DisplayDevice>, std::string> create(const DisplayDeviceOptions& options);
    ~DisplayDevice();
    DisplayDevice(const DisplayDevice&) = delete;
    DisplayDevice& operator=(const DisplayDevice&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    const std::string& name() const { return name_; }
    bool canImport() const { return externalMemory_; }
    // Validation errors of every display device of the process so far, those of their destruction
    // (objects left alive) included: read after the device is gone.
    static uint32_t validationErrors();

    uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags wanted) const;
    // Records commands into a command buffer of its own, submits them waiting for `wait` (a timeline
    // semaphore at `waitValue`, or none) and waits for the queue.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record, VkSemaphore wait = VK_NULL_HANDLE,
                       uint64_t waitValue = 0);

private:
    DisplayDevice() = default;
    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                    VkDebugUtilsMessageTypeFlagsEXT types,
                                                    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    std::string name_;
    bool externalMemory_ = false;
    VkPhysicalDeviceMemoryProperties memory_{};
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

// A render buffer's pixels on the display device: the plugin's exported memory imported (shared),
// or a host-visible buffer the host copies a mapping into (readback).
class DisplaySource {
public:
    // Takes over the descriptors in `exported` (closed on failure too).
    static std::variant<std::unique_ptr<DisplaySource>, std::string> import(DisplayDevice& device,
                                                                            const ObscuraExternalBuffer& exported);
    static std::unique_ptr<DisplaySource> upload(DisplayDevice& device, uint32_t width, uint32_t height,
                                                 ObscuraFormat format, VkDeviceSize size);
    ~DisplaySource();

    // readback: copies a mapped buffer's rows in.
    void copyFrom(const ObscuraMappedBuffer& mapped);
    // Commands before reading the buffer: the acquire from VK_QUEUE_FAMILY_EXTERNAL of imported memory.
    void recordAcquire(VkCommandBuffer cmd) const;
    VkBuffer buffer() const { return buffer_; }
    VkSemaphore semaphore() const { return semaphore_; }
    bool shared() const { return shared_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    ObscuraFormat format() const { return format_; }

private:
    explicit DisplaySource(DisplayDevice& device) : device_(device) {}
    DisplayDevice& device_;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkSemaphore semaphore_ = VK_NULL_HANDLE;  // the plugin's timeline, where it exports one
    void* mapped_ = nullptr;
    bool shared_ = false;
    uint32_t width_ = 0, height_ = 0;
    ObscuraFormat format_ = OBSCURA_FORMAT_UNKNOWN;
};

// aov_display.comp into an RGBA8 image of the source's size, left in TRANSFER_SRC_OPTIMAL layout.
class AovImage {
public:
    explicit AovImage(DisplayDevice& device);
    ~AovImage();
    AovImage(const AovImage&) = delete;
    AovImage& operator=(const AovImage&) = delete;

    void record(VkCommandBuffer cmd, const DisplaySource& source, AovView view);
    VkImage image() const { return image_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

private:
    void resize(uint32_t width, uint32_t height);
    DisplayDevice& device_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    uint32_t width_ = 0, height_ = 0;
};

// The AovView of an AOV name ("display", "depth", "normal", "motion", "primId").
AovView aovViewOf(const std::string& aov);

}  // namespace obscura::harness::view
