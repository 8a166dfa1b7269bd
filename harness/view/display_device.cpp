#include "harness/view/display_device.h"

#include "harness/view/aov_display_spv.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>

#include <unistd.h>

namespace obscura::harness::view {
namespace {

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

std::atomic<uint32_t> gValidationErrors{0};

}  // namespace

void check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(int(r)) + ")");
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags srcAccess,
                  VkAccessFlags dstAccess, VkPipelineStageFlags srcStage, VkPipelineStageFlags dstStage) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

uint32_t DisplayDevice::validationErrors() { return gValidationErrors.load(); }

VkBool32 DisplayDevice::onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        gValidationErrors.fetch_add(1);
        std::fprintf(stderr, "obscura: error: viewer: vulkan: %s\n", data && data->pMessage ? data->pMessage : "");
    }
    return VK_FALSE;
}

std::variant<std::unique_ptr<DisplayDevice>, std::string> DisplayDevice::create(const DisplayDeviceOptions& options) {
    std::unique_ptr<DisplayDevice> d(new DisplayDevice());
    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger.pfnUserCallback = &DisplayDevice::onMessage;
    messenger.pUserData = d.get();
    std::vector<const char*> extensions, layers;
    for (const auto& e : options.instanceExtensions) extensions.push_back(e.c_str());
    if (options.validation) {
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        layers.push_back("VK_LAYER_KHRONOS_validation");
    }
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "obscura view";
    app.apiVersion = VK_API_VERSION_1_3;
    // The messenger is chained so that messages of instance creation and destruction count too.
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, options.validation ? &messenger : nullptr};
    ici.pApplicationInfo = &app;
    ici.enabledExtensionCount = uint32_t(extensions.size());
    ici.ppEnabledExtensionNames = extensions.data();
    ici.enabledLayerCount = uint32_t(layers.size());
    ici.ppEnabledLayerNames = layers.data();
    if (vkCreateInstance(&ici, nullptr, &d->instance_) != VK_SUCCESS) return std::string("vkCreateInstance failed");
    if (options.validation) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(d->instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create || create(d->instance_, &messenger, nullptr, &d->messenger_) != VK_SUCCESS)
            return std::string("cannot create the validation messenger");
    }

    // The plugin's GPU: the one whose UUID its export names, else the one of its name.
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(d->instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(d->instance_, &count, devices.data());
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceIDProperties ids{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
        VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &ids};
        vkGetPhysicalDeviceProperties2(pd, &props);
        const bool match = options.deviceUUID ? std::memcmp(ids.deviceUUID, options.deviceUUID, VK_UUID_SIZE) == 0
                                              : options.deviceName == props.properties.deviceName;
        if (match) {
            d->physical_ = pd;
            d->name_ = props.properties.deviceName;
            break;
        }
    }
    if (!d->physical_) return "no Vulkan device of the viewer is the plugin's (" + options.deviceName + ")";

    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d->physical_, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(d->physical_, &familyCount, families.data());
    d->queueFamily_ = UINT32_MAX;
    for (uint32_t i = 0; i < familyCount && d->queueFamily_ == UINT32_MAX; ++i)
        if ((families[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
            (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT))
            d->queueFamily_ = i;
    if (d->queueFamily_ == UINT32_MAX) return d->name_ + " has no graphics and compute queue";

    std::vector<const char*> deviceExtensions;
    if (options.swapchain) deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    d->externalMemory_ = hasDeviceExtension(d->physical_, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    if (d->externalMemory_) deviceExtensions.push_back(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    const bool externalSemaphore = hasDeviceExtension(d->physical_, VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);
    if (externalSemaphore) deviceExtensions.push_back(VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);
    float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = d->queueFamily_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    // maintenance4: glslang's vulkan1.3 SPIR-V uses LocalSizeId.
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.maintenance4 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    f12.timelineSemaphore = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(d->physical_, &supported);
    features.features.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = uint32_t(deviceExtensions.size());
    dci.ppEnabledExtensionNames = deviceExtensions.data();
    if (vkCreateDevice(d->physical_, &dci, nullptr, &d->device_) != VK_SUCCESS)
        return "vkCreateDevice failed on " + d->name_;
    vkGetDeviceQueue(d->device_, d->queueFamily_, 0, &d->queue_);
    vkGetPhysicalDeviceMemoryProperties(d->physical_, &d->memory_);

    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = d->queueFamily_;
    check(vkCreateCommandPool(d->device_, &pci, nullptr, &d->pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = d->pool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(d->device_, &ai, &d->commands_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(d->device_, &fi, nullptr, &d->fence_), "vkCreateFence");
    return d;
}

DisplayDevice::~DisplayDevice() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        vkDestroyFence(device_, fence_, nullptr);
        vkDestroyCommandPool(device_, pool_, nullptr);
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

uint32_t DisplayDevice::memoryType(uint32_t typeBits, VkMemoryPropertyFlags wanted) const {
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
        if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    throw std::runtime_error("no memory type of " + name_ + " fits");
}

void DisplayDevice::submitAndWait(const std::function<void(VkCommandBuffer)>& record, VkSemaphore wait,
                                  uint64_t waitValue) {
    check(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(commands_, &bi), "vkBeginCommandBuffer");
    record(commands_);
    check(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
    VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    timeline.waitSemaphoreValueCount = 1;
    timeline.pWaitSemaphoreValues = &waitValue;
    VkPipelineStageFlags stage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO, wait ? &timeline : nullptr};
    si.waitSemaphoreCount = wait ? 1 : 0;
    si.pWaitSemaphores = &wait;
    si.pWaitDstStageMask = &stage;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &commands_;
    check(vkResetFences(device_, 1, &fence_), "vkResetFences");
    check(vkQueueSubmit(queue_, 1, &si, fence_), "vkQueueSubmit");
    check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

// --- DisplaySource ------------------------------------------------------------------------------

std::variant<std::unique_ptr<DisplaySource>, std::string> DisplaySource::import(DisplayDevice& device,
                                                                              const ObscuraExternalBuffer& e) {
    int memoryFd = e.memoryFd, semaphoreFd = e.semaphoreFd;
    auto fail = [&](const std::string& why) -> std::string {
        if (memoryFd >= 0) close(memoryFd);
        if (semaphoreFd >= 0) close(semaphoreFd);
        return why;
    };
    if (!device.canImport()) return fail(device.name() + " cannot import memory (no VK_KHR_external_memory_fd)");
    std::unique_ptr<DisplaySource> s(new DisplaySource(device));
    s->shared_ = true;
    s->width_ = e.width;
    s->height_ = e.height;
    s->format_ = e.format;
    VkDevice vk = device.device();
    VkExternalMemoryBufferCreateInfo external{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
    external.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, &external};
    bi.size = e.size;
    bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    if (vkCreateBuffer(vk, &bi, nullptr, &s->buffer_) != VK_SUCCESS) return fail("vkCreateBuffer (import) failed");
    VkMemoryDedicatedAllocateInfo dedicated{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO};
    dedicated.buffer = s->buffer_;
    VkImportMemoryFdInfoKHR importInfo{VK_STRUCTURE_TYPE_IMPORT_MEMORY_FD_INFO_KHR, e.dedicated ? &dedicated : nullptr};
    importInfo.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_OPAQUE_FD_BIT;
    importInfo.fd = memoryFd;
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &importInfo};
    ai.allocationSize = e.allocationSize;
    ai.memoryTypeIndex = e.memoryTypeIndex;
    if (vkAllocateMemory(vk, &ai, nullptr, &s->memory_) != VK_SUCCESS) return fail("importing the render buffer's memory failed");
    memoryFd = -1;  // the memory owns it now
    if (vkBindBufferMemory(vk, s->buffer_, s->memory_, 0) != VK_SUCCESS) return fail("vkBindBufferMemory (import) failed");
    if (semaphoreFd >= 0) {
        VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
        type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
        VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, &type};
        if (vkCreateSemaphore(vk, &si, nullptr, &s->semaphore_) != VK_SUCCESS) return fail("vkCreateSemaphore failed");
        auto importFd = reinterpret_cast<PFN_vkImportSemaphoreFdKHR>(vkGetDeviceProcAddr(vk, "vkImportSemaphoreFdKHR"));
        VkImportSemaphoreFdInfoKHR info{VK_STRUCTURE_TYPE_IMPORT_SEMAPHORE_FD_INFO_KHR};
        info.semaphore = s->semaphore_;
        info.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
        info.fd = semaphoreFd;
        if (!importFd || importFd(vk, &info) != VK_SUCCESS) return fail("importing the plugin's semaphore failed");
        semaphoreFd = -1;
    }
    return s;
}

std::unique_ptr<DisplaySource> DisplaySource::upload(DisplayDevice& device, uint32_t width, uint32_t height,
                                                     ObscuraFormat format, VkDeviceSize size) {
    std::unique_ptr<DisplaySource> s(new DisplaySource(device));
    s->width_ = width;
    s->height_ = height;
    s->format_ = format;
    VkDevice vk = device.device();
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = size;
    bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    check(vkCreateBuffer(vk, &bi, nullptr, &s->buffer_), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(vk, s->buffer_, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = device.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                    VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkAllocateMemory(vk, &ai, nullptr, &s->memory_), "vkAllocateMemory");
    check(vkBindBufferMemory(vk, s->buffer_, s->memory_, 0), "vkBindBufferMemory");
    check(vkMapMemory(vk, s->memory_, 0, VK_WHOLE_SIZE, 0, &s->mapped_), "vkMapMemory");
    return s;
}

DisplaySource::~DisplaySource() {
    VkDevice vk = device_.device();
    vkDeviceWaitIdle(vk);
    if (semaphore_) vkDestroySemaphore(vk, semaphore_, nullptr);
    if (buffer_) vkDestroyBuffer(vk, buffer_, nullptr);
    if (memory_) vkFreeMemory(vk, memory_, nullptr);
}

void DisplaySource::copyFrom(const ObscuraMappedBuffer& mapped) {
    // Both are tightly packed rows, top to bottom.
    std::memcpy(mapped_, mapped.data, mapped.rowStride * std::min(mapped.height, height_));
}

void DisplaySource::recordAcquire(VkCommandBuffer cmd) const {
    if (!shared_) return;
    // The other half of the plugin's release (gpu/external_memory.cpp): ownership from
    // VK_QUEUE_FAMILY_EXTERNAL, the frame's writes made visible to the shader.
    VkBufferMemoryBarrier barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    barrier.srcAccessMask = 0;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_EXTERNAL;
    barrier.dstQueueFamilyIndex = device_.queueFamily();
    barrier.buffer = buffer_;
    barrier.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 1,
                         &barrier, 0, nullptr);
}

// --- AovImage -----------------------------------------------------------------------------------

struct AovPush {
    uint32_t view, width, height;
    float motionScale;
};

AovImage::AovImage(DisplayDevice& device) : device_(device) {
    VkDevice vk = device.device();
    VkDescriptorSetLayoutBinding bindings[2] = {
        {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
    VkDescriptorSetLayoutCreateInfo dl{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    dl.bindingCount = 2;
    dl.pBindings = bindings;
    check(vkCreateDescriptorSetLayout(vk, &dl, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(AovPush)};
    VkPipelineLayoutCreateInfo pl{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pl.setLayoutCount = 1;
    pl.pSetLayouts = &setLayout_;
    pl.pushConstantRangeCount = 1;
    pl.pPushConstantRanges = &range;
    check(vkCreatePipelineLayout(vk, &pl, nullptr, &layout_), "vkCreatePipelineLayout");
    VkShaderModuleCreateInfo sm{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    sm.codeSize = sizeof(kAovDisplaySpirv);
    sm.pCode = kAovDisplaySpirv;
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(vk, &sm, nullptr, &module), "vkCreateShaderModule");
    VkComputePipelineCreateInfo cp{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    cp.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module,
                "main", nullptr};
    cp.layout = layout_;
    VkResult r = vkCreateComputePipelines(vk, VK_NULL_HANDLE, 1, &cp, nullptr, &pipeline_);
    vkDestroyShaderModule(vk, module, nullptr);
    check(r, "vkCreateComputePipelines");
    VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1}};
    VkDescriptorPoolCreateInfo dp{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dp.maxSets = 1;
    dp.poolSizeCount = 2;
    dp.pPoolSizes = sizes;
    check(vkCreateDescriptorPool(vk, &dp, nullptr, &pool_), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo da{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    da.descriptorPool = pool_;
    da.descriptorSetCount = 1;
    da.pSetLayouts = &setLayout_;
    check(vkAllocateDescriptorSets(vk, &da, &set_), "vkAllocateDescriptorSets");
}

AovImage::~AovImage() {
    VkDevice vk = device_.device();
    vkDeviceWaitIdle(vk);
    resize(0, 0);
    vkDestroyDescriptorPool(vk, pool_, nullptr);
    vkDestroyPipeline(vk, pipeline_, nullptr);
    vkDestroyPipelineLayout(vk, layout_, nullptr);
    vkDestroyDescriptorSetLayout(vk, setLayout_, nullptr);
}

void AovImage::resize(uint32_t width, uint32_t height) {
    VkDevice vk = device_.device();
    if (image_) {
        vkDeviceWaitIdle(vk);
        vkDestroyImageView(vk, view_, nullptr);
        vkDestroyImage(vk, image_, nullptr);
        vkFreeMemory(vk, memory_, nullptr);
        image_ = VK_NULL_HANDLE;
    }
    width_ = width;
    height_ = height;
    if (width == 0 || height == 0) return;
    VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = VK_FORMAT_R8G8B8A8_UNORM;
    ii.extent = {width, height, 1};
    ii.mipLevels = 1;
    ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    check(vkCreateImage(vk, &ii, nullptr, &image_), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(vk, image_, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = device_.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkAllocateMemory(vk, &ai, nullptr, &memory_), "vkAllocateMemory");
    check(vkBindImageMemory(vk, image_, memory_, 0), "vkBindImageMemory");
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image_;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = ii.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    check(vkCreateImageView(vk, &vi, nullptr, &view_), "vkCreateImageView");
}

void AovImage::record(VkCommandBuffer cmd, const DisplaySource& source, AovView view) {
    if (source.width() != width_ || source.height() != height_) resize(source.width(), source.height());
    VkDescriptorBufferInfo bufferInfo{source.buffer(), 0, VK_WHOLE_SIZE};
    VkDescriptorImageInfo imageInfo{VK_NULL_HANDLE, view_, VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                      {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    writes[0].dstSet = writes[1].dstSet = set_;
    writes[0].dstBinding = 0;
    writes[0].descriptorCount = 1;
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[0].pBufferInfo = &bufferInfo;
    writes[1].dstBinding = 1;
    writes[1].descriptorCount = 1;
    writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    writes[1].pImageInfo = &imageInfo;
    // The set is rewritten between submissions only: every recording is submitted and waited for.
    vkUpdateDescriptorSets(device_.device(), 2, writes, 0, nullptr);

    source.recordAcquire(cmd);
    imageBarrier(cmd, image_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_ACCESS_TRANSFER_READ_BIT,
                 VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
    AovPush push{uint32_t(view), width_, height_, 16.0f};
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, (width_ + 7) / 8, (height_ + 7) / 8, 1);
    imageBarrier(cmd, image_, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
}

AovView aovViewOf(const std::string& aov) {
    if (aov == "depth") return AovView::Depth;
    if (aov == "normal") return AovView::Normal;
    if (aov == "motion") return AovView::Motion;
    if (aov == "primId" || aov == "instanceId") return AovView::PrimId;
    return AovView::Display;
}

}  // namespace obscura::harness::view
