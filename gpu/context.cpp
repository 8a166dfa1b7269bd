#include "gpu/context.h"

#include "gpu/pipeline_statistics.h"

#include "gpu/vk_check.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace obscura::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

VkResult createInstance(bool validation, const VkDebugUtilsMessengerCreateInfoEXT* messengerInfo,
                        VkInstance* out) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "obscura";
    app.pEngineName = "obscura";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    if (validation) {
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    // Chained so that messages of instance creation and destruction are caught too.
    ci.pNext = messengerInfo;
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = static_cast<uint32_t>(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    VkResult r = vkCreateInstance(&ci, nullptr, out);
    if (r == VK_SUCCESS) vk::addInstance(*out);
    return r;
}

// Destroys an instance and drops its table.
void destroyInstance(VkInstance instance) {
    const void* key = vk::dispatchKey(instance);
    vkDestroyInstance(instance, nullptr);
    vk::forget(key);
}

PhysicalDeviceSummary summarise(VkPhysicalDevice pd) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
    vkGetPhysicalDeviceProperties2(pd, &props);
    PhysicalDeviceSummary s;
    s.name = props.properties.deviceName;
    s.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    s.apiVersion = props.properties.apiVersion;
    s.discrete = props.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
    s.cpu = props.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    s.msaaSamples = props.properties.limits.framebufferColorSampleCounts &
                    props.properties.limits.framebufferDepthSampleCounts;
    return s;
}

int typeRank(VkPhysicalDevice pd) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    switch (p.deviceType) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

bool hasExtension(VkPhysicalDevice pd, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &count, extensions.data());
    for (const auto& e : extensions)
        if (std::strcmp(e.extensionName, name) == 0) return true;
    return false;
}

// Vulkan 1.3 features, and push descriptors for per-draw material textures (arrays of samplers
// indexed per draw would need shaderSampledImageArrayDynamicIndexing, which lavapipe lacks).
bool meetsRequirements(VkPhysicalDevice pd) {
    if (!hasExtension(pd, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) return false;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13};
    vkGetPhysicalDeviceFeatures2(pd, &f);
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(pd, &p);
    return p.apiVersion >= VK_API_VERSION_1_3 && f13.dynamicRendering && f13.synchronization2 && f13.maintenance4;
}

// OBSCURA_DEVICE / the create-info selector: an index into the device list or a name substring.
Result<VkPhysicalDevice> pickDevice(const std::vector<VkPhysicalDevice>& devices, const std::string& selector) {
    std::vector<VkPhysicalDevice> usable;
    for (VkPhysicalDevice pd : devices)
        if (meetsRequirements(pd)) usable.push_back(pd);
    if (usable.empty())
        return Failure{"no Vulkan 1.3 device with dynamic rendering, synchronization2 and VK_KHR_push_descriptor"};
    if (!selector.empty()) {
        char* end = nullptr;
        unsigned long index = std::strtoul(selector.c_str(), &end, 10);
        if (end && *end == '\0') {
            if (index >= devices.size()) return Failure{"device index " + selector + " out of range"};
            if (!meetsRequirements(devices[index]))
                return Failure{"device " + selector + " lacks Vulkan 1.3 features or VK_KHR_push_descriptor"};
            return devices[index];
        }
        for (VkPhysicalDevice pd : usable)
            if (summarise(pd).name.find(selector) != std::string::npos) return pd;
        return Failure{"no Vulkan device matches '" + selector + "'"};
    }
    // Discrete GPU first, lavapipe (CPU) last.
    std::stable_sort(usable.begin(), usable.end(), [](VkPhysicalDevice a, VkPhysicalDevice b) {
        return typeRank(a) < typeRank(b);
    });
    return usable.front();
}

// Opaque fds of memory and of timeline semaphores, where the driver offers them (lavapipe 22.3 offers
// memory only; NVIDIA both).
ExternalHandleSupport externalHandleSupport(VkPhysicalDevice pd) {
    ExternalHandleSupport s;
    s.memoryFd = hasExtension(pd, VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    if (hasExtension(pd, VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME)) {
        VkSemaphoreTypeCreateInfo timeline{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
        timeline.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
        VkPhysicalDeviceExternalSemaphoreInfo info{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_SEMAPHORE_INFO, &timeline};
        info.handleType = VK_EXTERNAL_SEMAPHORE_HANDLE_TYPE_OPAQUE_FD_BIT;
        VkExternalSemaphoreProperties properties{VK_STRUCTURE_TYPE_EXTERNAL_SEMAPHORE_PROPERTIES};
        vkGetPhysicalDeviceExternalSemaphoreProperties(pd, &info, &properties);
        s.semaphoreFd = (properties.externalSemaphoreFeatures & VK_EXTERNAL_SEMAPHORE_FEATURE_EXPORTABLE_BIT) != 0;
    }
    VkPhysicalDeviceIDProperties ids{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &ids};
    vkGetPhysicalDeviceProperties2(pd, &props);
    std::memcpy(s.deviceUUID, ids.deviceUUID, VK_UUID_SIZE);
    std::memcpy(s.driverUUID, ids.driverUUID, VK_UUID_SIZE);
    return s;
}

uint32_t pickQueueFamily(VkPhysicalDevice pd) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need && families[i].timestampValidBits > 0) return i;
    }
    for (uint32_t i = 0; i < count; ++i)
        if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) return i;
    return UINT32_MAX;
}

}  // namespace

VkBool32 Context::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
                                const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* self = static_cast<Context*>(user);
    std::string msg = std::string("vulkan: ") + (data && data->pMessage ? data->pMessage : "");
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        self->validationErrors_.fetch_add(1);
        self->log(LogLevel::Error, msg);
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        self->log(LogLevel::Warning, msg);
    }
    return VK_FALSE;
}

void Context::log(LogLevel level, const std::string& message) const {
    {
        std::lock_guard lock(heldMutex_);
        if (holders_ > 0) {
            heldMessages_.emplace_back(level, message);
            return;
        }
    }
    if (log_) log_(level, message);
}

Context::HeldLog::HeldLog(const Context& context) : context_(context) {
    std::lock_guard lock(context_.heldMutex_);
    ++context_.holders_;
}

Context::HeldLog::~HeldLog() {
    std::vector<std::pair<LogLevel, std::string>> messages;
    {
        std::lock_guard lock(context_.heldMutex_);
        if (--context_.holders_ > 0) return;
        messages.swap(context_.heldMessages_);
    }
    for (const auto& [level, message] : messages) context_.log(level, message);
}

// LeakSanitizer walks allocation stacks at exit; when the loader has unloaded lavapipe (and the
// LLVM it links) at vkDestroyInstance those frames point into unmapped code and every one-time
// allocation of the driver reads as a leak. Sanitized builds keep the driver and the validation
// layer resident so the suppressions in tests/lsan.supp can name them.
static void pinDriversForLeakChecking() {
#if defined(__SANITIZE_ADDRESS__)
    static const bool pinned = [] {
        dlopen("libvulkan_lvp.so", RTLD_NOW | RTLD_NODELETE);
        dlopen("libVkLayer_khronos_validation.so", RTLD_NOW | RTLD_NODELETE);
        return true;
    }();
    (void)pinned;
#endif
}

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
    pinDriversForLeakChecking();
    if (std::string problem = vk::openLoader(); !problem.empty()) return Failure{problem};
    std::unique_ptr<Context> ctx(new Context());
    ctx->log_ = options.log;
    ctx->faults_ = options.faults;
    bool validation = options.validation;
    if (validation && !hasLayer(kValidationLayer)) {
        return Failure{"validation requested but VK_LAYER_KHRONOS_validation is not installed"};
    }
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = &Context::debugCallback;
    messengerInfo.pUserData = ctx.get();

    VkResult r = createInstance(validation, validation ? &messengerInfo : nullptr, &ctx->instance_);
    if (r != VK_SUCCESS) return Failure{std::string("vkCreateInstance failed: ") + vkResultName(r)};
    if (validation) {
        auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx->instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!createMessenger || createMessenger(ctx->instance_, &messengerInfo, nullptr, &ctx->messenger_) != VK_SUCCESS)
            return Failure{"cannot create the validation debug messenger"};
    }

    uint32_t count = 0;
    vkEnumeratePhysicalDevices(ctx->instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(ctx->instance_, &count, devices.data());
    if (devices.empty()) return Failure{"no Vulkan device (is mesa-vulkan-drivers installed?)"};
    std::string selector = options.deviceSelector;
    if (selector.empty()) {
        if (const char* env = std::getenv("OBSCURA_DEVICE")) selector = env;
    }
    auto picked = pickDevice(devices, selector);
    if (!picked) return Failure{picked.error()};
    ctx->physical_ = *picked;
    ctx->summary_ = summarise(ctx->physical_);
    vkGetPhysicalDeviceProperties(ctx->physical_, &ctx->properties_);
    vkGetPhysicalDeviceMemoryProperties(ctx->physical_, &ctx->memoryProperties_);

    ctx->queueFamily_ = pickQueueFamily(ctx->physical_);
    if (ctx->queueFamily_ == UINT32_MAX) return Failure{"device has no graphics queue"};
    float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = ctx->queueFamily_;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;

    // maintenance4: glslang's vulkan1.3 SPIR-V uses LocalSizeId.
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    f13.maintenance4 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    f12.hostQueryReset = VK_TRUE;
    f12.scalarBlockLayout = VK_TRUE;
    ctx->externalHandles_ = externalHandleSupport(ctx->physical_);
    f12.timelineSemaphore = ctx->externalHandles_.semaphoreFd ? VK_TRUE : VK_FALSE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
    VkPhysicalDeviceFeatures supported{};
    vkGetPhysicalDeviceFeatures(ctx->physical_, &supported);
    features.features.sampleRateShading = supported.sampleRateShading;
    features.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    features.features.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
    // Static geometry leaves the velocity target untouched while writing the others (motion blur).
    features.features.independentBlend = supported.independentBlend;
    // Material textures are filtered anisotropically where the device can, except on a CPU device:
    // lavapipe's anisotropic filter mixes in the lookups of the pixel's quad neighbours and ignores
    // explicit gradients, so a magnified or frontal texture's edge spreads over two pixels (22% of
    // a check's edge in the next pixel where trilinear puts 10%) and no LOD bias can narrow it.
    features.features.samplerAnisotropy =
        supported.samplerAnisotropy && ctx->properties_.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU;
    // Normal maps are BC5-compressed where the device samples it.
    features.features.textureCompressionBC = supported.textureCompressionBC;
    ctx->enabledFeatures_ = features.features;
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executableInfo{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
    const bool statistics = pipelineStatisticsRequested() &&
                            hasExtension(ctx->physical_, VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    if (statistics) {
        executableInfo.pipelineExecutableInfo = VK_TRUE;
        f13.pNext = &executableInfo;
    }

    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    std::vector<const char*> deviceExtensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    if (ctx->externalHandles_.memoryFd) deviceExtensions.push_back(VK_KHR_EXTERNAL_MEMORY_FD_EXTENSION_NAME);
    if (ctx->externalHandles_.semaphoreFd) deviceExtensions.push_back(VK_KHR_EXTERNAL_SEMAPHORE_FD_EXTENSION_NAME);
    if (statistics) deviceExtensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    dci.enabledExtensionCount = static_cast<uint32_t>(deviceExtensions.size());
    dci.ppEnabledExtensionNames = deviceExtensions.data();
    r = vkCreateDevice(ctx->physical_, &dci, nullptr, &ctx->device_);
    if (r != VK_SUCCESS) return Failure{std::string("vkCreateDevice failed: ") + vkResultName(r)};
    vk::addDevice(ctx->instance_, ctx->device_);
    vkGetDeviceQueue(ctx->device_, ctx->queueFamily_, 0, &ctx->queue_);
    ctx->cmdPushDescriptorSet_ = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(ctx->device_, "vkCmdPushDescriptorSetKHR"));
    if (statistics) {
        ctx->pipelineExecutables_.properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
            vkGetDeviceProcAddr(ctx->device_, "vkGetPipelineExecutablePropertiesKHR"));
        ctx->pipelineExecutables_.statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
            vkGetDeviceProcAddr(ctx->device_, "vkGetPipelineExecutableStatisticsKHR"));
    }

    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = ctx->queueFamily_;
    vkCheck(vkCreateCommandPool(ctx->device_, &pci, nullptr, &ctx->commandPool_), "vkCreateCommandPool");
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vkCheck(vkCreateFence(ctx->device_, &fci, nullptr, &ctx->fence_), "vkCreateFence");
    return ctx;
}

Result<std::vector<PhysicalDeviceSummary>> Context::enumerate() {
    pinDriversForLeakChecking();
    if (std::string problem = vk::openLoader(); !problem.empty()) return Failure{problem};
    VkInstance instance = VK_NULL_HANDLE;
    VkResult r = createInstance(false, nullptr, &instance);
    if (r != VK_SUCCESS) return Failure{std::string("vkCreateInstance failed: ") + vkResultName(r)};
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    std::vector<PhysicalDeviceSummary> out;
    for (VkPhysicalDevice pd : devices) out.push_back(summarise(pd));
    destroyInstance(instance);
    return out;
}

Context::~Context() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        vkDestroyFence(device_, fence_, nullptr);
        vkDestroyCommandPool(device_, commandPool_, nullptr);
        const void* key = vk::dispatchKey(device_);
        vkDestroyDevice(device_, nullptr);
        vk::forget(key);
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
    }
    if (instance_) destroyInstance(instance_);
}

void Context::beginOneShot(VkCommandBuffer& cmd) {
    // One command buffer, allocated once and reset for each submission: a steady frame creates no
    // Vulkan object (issue 13).
    if (!oneShot_) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = commandPool_;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        vkCheck(vkAllocateCommandBuffers(device_, &ai, &oneShot_), "vkAllocateCommandBuffers");
    } else {
        vkCheck(vkResetCommandBuffer(oneShot_, 0), "vkResetCommandBuffer");
    }
    cmd = oneShot_;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
}

void Context::endOneShot(VkCommandBuffer cmd) {
    vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    vkCheck(vkResetFences(device_, 1, &fence_), "vkResetFences");
    if (faults_.strikes(FaultInjection::Kind::DeviceLost))
        vkCheck(VK_ERROR_DEVICE_LOST, "vkQueueSubmit (OBSCURA_FAULT_INJECTION)");
    vkCheck(vkQueueSubmit(queue_, 1, &si, fence_), "vkQueueSubmit");
    vkCheck(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

const char* vkResultName(VkResult r) {
    switch (r) {
        case VK_SUCCESS: return "VK_SUCCESS";
        case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
        case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
        case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
        case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
        case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
        case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
        case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
        case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
        case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
        case VK_TIMEOUT: return "VK_TIMEOUT";
        case VK_NOT_READY: return "VK_NOT_READY";
        default: return "VkResult error";
    }
}

}  // namespace obscura::gpu
