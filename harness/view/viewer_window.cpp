#include "harness/view/viewer_window.h"

#include "harness/image/png_io.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace obscura::harness::view {
namespace {

void checkImgui(VkResult r) { check(r, "Dear ImGui's Vulkan renderer"); }

}  // namespace

std::variant<std::unique_ptr<ViewerWindow>, std::string> ViewerWindow::open(int width, int height,
                                                                            const std::string& title) {
    if (!glfwInit()) return std::string("cannot open a window: no display (set DISPLAY, or run under xvfb-run)");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        return std::string("GLFW finds no Vulkan loader");
    }
    std::unique_ptr<ViewerWindow> w(new ViewerWindow());
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    w->window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!w->window_) {
        glfwTerminate();
        return std::string("glfwCreateWindow failed");
    }
    // Where the window manager allows it, at the screen's corner (a screenshot of the screen finds it there).
    glfwSetWindowPos(w->window_, 0, 0);
    return w;
}

ViewerWindow::~ViewerWindow() {
    detach();
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

std::vector<std::string> ViewerWindow::instanceExtensions() const {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    return std::vector<std::string>(names, names + count);
}

void ViewerWindow::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

void ViewerWindow::attach(DisplayDevice& device) {
    device_ = &device;
    VkDevice vk = device.device();
    check(glfwCreateWindowSurface(device.instance(), window_, nullptr, &surface_), "glfwCreateWindowSurface");
    VkBool32 supported = VK_FALSE;
    vkGetPhysicalDeviceSurfaceSupportKHR(device.physicalDevice(), device.queueFamily(), surface_, &supported);
    if (!supported) throw std::runtime_error(device.name() + " cannot present to this window");
    uint32_t count = 0;
    vkGetPhysicalDeviceSurfaceFormatsKHR(device.physicalDevice(), surface_, &count, nullptr);
    std::vector<VkSurfaceFormatKHR> formats(count);
    vkGetPhysicalDeviceSurfaceFormatsKHR(device.physicalDevice(), surface_, &count, formats.data());
    // UNORM, not sRGB: the display AOV is already encoded for the display (the OCIO view).
    for (const auto& f : formats)
        if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) format_ = f.format;
    if (format_ == VK_FORMAT_UNDEFINED) throw std::runtime_error("the window offers no 8-bit UNORM format");

    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = device.queueFamily();
    check(vkCreateCommandPool(vk, &pci, nullptr, &pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = pool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(vk, &ai, &commands_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(vk, &fi, nullptr, &fence_), "vkCreateFence");
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    check(vkCreateSemaphore(vk, &si, nullptr, &imageAvailable_), "vkCreateSemaphore");

    // The HUD draws over the blitted image: loaded, then presented.
    VkAttachmentDescription colour{};
    colour.format = format_;
    colour.samples = VK_SAMPLE_COUNT_1_BIT;
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    colour.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    colour.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    VkSubpassDependency afterBlit{};
    afterBlit.srcSubpass = VK_SUBPASS_EXTERNAL;
    afterBlit.dstSubpass = 0;
    afterBlit.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    afterBlit.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    afterBlit.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    afterBlit.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    rp.attachmentCount = 1;
    rp.pAttachments = &colour;
    rp.subpassCount = 1;
    rp.pSubpasses = &subpass;
    rp.dependencyCount = 1;
    rp.pDependencies = &afterBlit;
    check(vkCreateRenderPass(vk, &rp, nullptr, &hudPass_), "vkCreateRenderPass");
    createSwapchain();

    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}};
    VkDescriptorPoolCreateInfo dp{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dp.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    dp.maxSets = 8;
    dp.poolSizeCount = 1;
    dp.pPoolSizes = sizes;
    check(vkCreateDescriptorPool(vk, &dp, nullptr, &hudPool_), "vkCreateDescriptorPool");
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the scene
    ImGui::StyleColorsDark();
    // After the viewer's own GLFW callbacks: Dear ImGui chains to them.
    ImGui_ImplGlfw_InitForVulkan(window_, true);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = device.instance();
    info.PhysicalDevice = device.physicalDevice();
    info.Device = vk;
    info.QueueFamily = device.queueFamily();
    info.Queue = device.queue();
    info.DescriptorPool = hudPool_;
    info.MinImageCount = 2;
    info.ImageCount = uint32_t(images_.size());
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = &checkImgui;
    ImGui_ImplVulkan_Init(&info, hudPass_);
    device.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

void ViewerWindow::createSwapchain() {
    VkDevice vk = device_->device();
    VkSurfaceCapabilitiesKHR caps;
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device_->physicalDevice(), surface_, &caps),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    int width = 0, height = 0;
    framebufferSize(width, height);
    extent_ = caps.currentExtent.width != UINT32_MAX ? caps.currentExtent
                                                     : VkExtent2D{uint32_t(width), uint32_t(height)};
    uint32_t modeCount = 0;
    vkGetPhysicalDeviceSurfacePresentModesKHR(device_->physicalDevice(), surface_, &modeCount, nullptr);
    std::vector<VkPresentModeKHR> modes(modeCount);
    vkGetPhysicalDeviceSurfacePresentModesKHR(device_->physicalDevice(), surface_, &modeCount, modes.data());
    // The renderer paces the frames (a frame takes longer than a refresh on a CPU device); FIFO is
    // the one mode every device has.
    VkPresentModeKHR mode = std::count(modes.begin(), modes.end(), VK_PRESENT_MODE_IMMEDIATE_KHR)
                                ? VK_PRESENT_MODE_IMMEDIATE_KHR
                                : VK_PRESENT_MODE_FIFO_KHR;
    VkSwapchainCreateInfoKHR sci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    sci.surface = surface_;
    sci.minImageCount = std::max(caps.minImageCount, 2u);
    if (caps.maxImageCount) sci.minImageCount = std::min(sci.minImageCount, caps.maxImageCount);
    sci.imageFormat = format_;
    sci.imageColorSpace = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    sci.imageExtent = extent_;
    sci.imageArrayLayers = 1;
    // Transfer source: screenshots copy the presented image.
    sci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                     (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
    sci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    sci.preTransform = caps.currentTransform;
    sci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    sci.presentMode = mode;
    sci.clipped = VK_TRUE;
    check(vkCreateSwapchainKHR(vk, &sci, nullptr, &swapchain_), "vkCreateSwapchainKHR");
    uint32_t count = 0;
    vkGetSwapchainImagesKHR(vk, swapchain_, &count, nullptr);
    images_.resize(count);
    vkGetSwapchainImagesKHR(vk, swapchain_, &count, images_.data());
    for (VkImage image : images_) {
        VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vi.image = image;
        vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
        vi.format = format_;
        vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        check(vkCreateImageView(vk, &vi, nullptr, &view), "vkCreateImageView");
        views_.push_back(view);
        VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        fb.renderPass = hudPass_;
        fb.attachmentCount = 1;
        fb.pAttachments = &view;
        fb.width = extent_.width;
        fb.height = extent_.height;
        fb.layers = 1;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        check(vkCreateFramebuffer(vk, &fb, nullptr, &framebuffer), "vkCreateFramebuffer");
        framebuffers_.push_back(framebuffer);
        VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore semaphore = VK_NULL_HANDLE;
        check(vkCreateSemaphore(vk, &si, nullptr, &semaphore), "vkCreateSemaphore");
        renderFinished_.push_back(semaphore);
    }
}

void ViewerWindow::destroySwapchain() {
    VkDevice vk = device_->device();
    vkDeviceWaitIdle(vk);
    for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(vk, f, nullptr);
    for (VkImageView v : views_) vkDestroyImageView(vk, v, nullptr);
    for (VkSemaphore s : renderFinished_) vkDestroySemaphore(vk, s, nullptr);
    framebuffers_.clear();
    views_.clear();
    renderFinished_.clear();
    images_.clear();
    if (swapchain_) vkDestroySwapchainKHR(vk, swapchain_, nullptr);
    swapchain_ = VK_NULL_HANDLE;
}

void ViewerWindow::detach() {
    if (!device_) return;
    VkDevice vk = device_->device();
    vkDeviceWaitIdle(vk);
    if (hudStarted_) ImGui::EndFrame();
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    destroySwapchain();
    vkDestroyDescriptorPool(vk, hudPool_, nullptr);
    vkDestroyRenderPass(vk, hudPass_, nullptr);
    vkDestroySemaphore(vk, imageAvailable_, nullptr);
    vkDestroyFence(vk, fence_, nullptr);
    vkDestroyCommandPool(vk, pool_, nullptr);
    vkDestroySurfaceKHR(device_->instance(), surface_, nullptr);
    device_ = nullptr;
}

void ViewerWindow::beginHud() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    hudStarted_ = true;
}

void ViewerWindow::present(const AovImage& image, bool hud, const std::string& screenshot, VkSemaphore wait,
                           uint64_t waitValue) {
    VkDevice vk = device_->device();
    int width = 0, height = 0;
    framebufferSize(width, height);
    if (uint32_t(width) != extent_.width || uint32_t(height) != extent_.height) {
        destroySwapchain();
        createSwapchain();
    }
    ImGui::Render();
    hudStarted_ = false;
    uint32_t index = 0;
    VkResult acquired = vkAcquireNextImageKHR(vk, swapchain_, UINT64_MAX, imageAvailable_, VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) return;  // resized meanwhile: the next frame recreates it
    if (acquired != VK_SUBOPTIMAL_KHR) check(acquired, "vkAcquireNextImageKHR");

    const bool capture = !screenshot.empty();
    VkBuffer captureBuffer = VK_NULL_HANDLE;
    VkDeviceMemory captureMemory = VK_NULL_HANDLE;
    if (capture) {
        VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        bi.size = VkDeviceSize(extent_.width) * extent_.height * 4;
        bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        check(vkCreateBuffer(vk, &bi, nullptr, &captureBuffer), "vkCreateBuffer");
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(vk, captureBuffer, &req);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = device_->memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                         VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        check(vkAllocateMemory(vk, &ai, nullptr, &captureMemory), "vkAllocateMemory");
        check(vkBindBufferMemory(vk, captureBuffer, captureMemory, 0), "vkBindBufferMemory");
    }

    VkCommandBuffer cmd = commands_;
    check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    VkImage target = images_[index];
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                 VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
    // The image fills the window; it is the window's size except for the frame after a resize.
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(image.width()), int32_t(image.height()), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int32_t(extent_.width), int32_t(extent_.height), 1};
    vkCmdBlitImage(cmd, image.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   1, &blit, VK_FILTER_NEAREST);
    VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rp.renderPass = hudPass_;
    rp.framebuffer = framebuffers_[index];
    rp.renderArea.extent = extent_;
    vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    if (hud) ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
    if (capture) {
        imageBarrier(cmd, target, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                     VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {extent_.width, extent_.height, 1};
        vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, captureBuffer, 1, &copy);
        imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                     VK_ACCESS_TRANSFER_READ_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
    }
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

    VkSemaphore waits[2] = {imageAvailable_, wait};
    VkPipelineStageFlags stages[2] = {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT};
    uint64_t values[2] = {0, waitValue};
    VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    timeline.waitSemaphoreValueCount = wait ? 2 : 1;
    timeline.pWaitSemaphoreValues = values;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO, wait ? &timeline : nullptr};
    si.waitSemaphoreCount = wait ? 2 : 1;
    si.pWaitSemaphores = waits;
    si.pWaitDstStageMask = stages;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    si.signalSemaphoreCount = 1;
    si.pSignalSemaphores = &renderFinished_[index];
    check(vkResetFences(vk, 1, &fence_), "vkResetFences");
    check(vkQueueSubmit(device_->queue(), 1, &si, fence_), "vkQueueSubmit");
    VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &renderFinished_[index];
    pi.swapchainCount = 1;
    pi.pSwapchains = &swapchain_;
    pi.pImageIndices = &index;
    VkResult presented = vkQueuePresentKHR(device_->queue(), &pi);
    if (presented != VK_ERROR_OUT_OF_DATE_KHR && presented != VK_SUBOPTIMAL_KHR) check(presented, "vkQueuePresentKHR");
    check(vkWaitForFences(vk, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    if (capture) {
        writeScreenshot(screenshot, captureMemory);
        vkDestroyBuffer(vk, captureBuffer, nullptr);
        vkFreeMemory(vk, captureMemory, nullptr);
    }
}

void ViewerWindow::writeScreenshot(const std::string& path, VkDeviceMemory memory) {
    void* mapped = nullptr;
    check(vkMapMemory(device_->device(), memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    std::vector<uint8_t> rgba(size_t(extent_.width) * extent_.height * 4);
    std::memcpy(rgba.data(), mapped, rgba.size());
    vkUnmapMemory(device_->device(), memory);
    for (size_t i = 0; i < rgba.size(); i += 4) {
        if (format_ == VK_FORMAT_B8G8R8A8_UNORM) std::swap(rgba[i], rgba[i + 2]);
        rgba[i + 3] = 255;  // the window is opaque
    }
    auto status = image::writePng(path, int(extent_.width), int(extent_.height), image::PngFormat::Rgba, rgba.data(),
                                  size_t(extent_.width) * 4);
    if (image::isError(status)) throw std::runtime_error("cannot write " + path + ": " + image::errorOf(status));
}

}  // namespace obscura::harness::view
