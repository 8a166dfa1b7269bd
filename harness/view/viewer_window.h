// The viewer's window: GLFW for the window and its input, a Vulkan swapchain on the display
// device, the shown AOV blitted into it and Dear ImGui's HUD drawn over it.
#pragma once

#include "harness/view/display_device.h"

#include <memory>
#include <string>
#include <variant>
#include <vector>

struct GLFWwindow;

namespace obscura::harness::view {

class ViewerWindow {
public:
    // Opens the window (no Vulkan yet: the display device is made for the plugin's GPU later).
    static std::variant<std::unique_ptr<ViewerWindow>, std::string> open(int width, int height, const std::string& title);
    ~ViewerWindow();
    ViewerWindow(const ViewerWindow&) = delete;
    ViewerWindow& operator=(const ViewerWindow&) = delete;

    GLFWwindow* glfw() const { return window_; }
    // The instance extensions a surface of this window needs.
    std::vector<std::string> instanceExtensions() const;
    // Makes the surface, the swapchain and the HUD's renderer on `device`.
    void attach(DisplayDevice& device);
    // Releases every Vulkan object of the window (before the display device goes).
    void detach();
    void framebufferSize(int& width, int& height) const;

    // Starts the HUD's frame: Dear ImGui widgets may be built until present().
    void beginHud();
    // Shows `image` (scaled to the window), the HUD over it when `hud`, and writes the presented
    // image to `screenshot` (PNG) when not empty. Waits for `source`'s semaphore at `waitValue`.
    void present(const AovImage& image, bool hud, const std::string& screenshot, VkSemaphore wait = VK_NULL_HANDLE,
                 uint64_t waitValue = 0);

private:
    ViewerWindow() = default;
    void createSwapchain();
    void destroySwapchain();
    void writeScreenshot(const std::string& path, VkDeviceMemory memory);

    GLFWwindow* window_ = nullptr;
    DisplayDevice* device_ = nullptr;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_{};
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkFramebuffer> framebuffers_;
    std::vector<VkSemaphore> renderFinished_;  // one per swapchain image
    VkRenderPass hudPass_ = VK_NULL_HANDLE;
    VkDescriptorPool hudPool_ = VK_NULL_HANDLE;
    VkSemaphore imageAvailable_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    bool hudStarted_ = false;
};

}  // namespace obscura::harness::view
