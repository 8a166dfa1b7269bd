#include "gpu/vulkan_functions.h"

#include <dlfcn.h>

#include <array>
#include <atomic>
#include <mutex>
#include <stdexcept>

namespace obscura::gpu::vk {
namespace {

LoaderTable gLoader;

// A few instances and devices live at once (one each per delegate, and a probe instance for
// `obscura info`); a fixed array keeps lookups lock-free: a slot's table is written before its key
// is published and never while the key is set.
constexpr size_t kSlots = 64;

template <typename Table>
struct Slot {
    std::atomic<const void*> key{nullptr};
    Table table;
};

std::array<Slot<InstanceTable>, kSlots> gInstances;
std::array<Slot<DeviceTable>, kSlots> gDevices;
std::mutex gSlotsMutex;

template <typename Table>
Table& claim(std::array<Slot<Table>, kSlots>& slots, std::atomic<const void*>*& published) {
    for (Slot<Table>& slot : slots)
        if (!slot.key.load(std::memory_order_relaxed)) {
            published = &slot.key;
            slot.table = Table{};
            return slot.table;
        }
    throw std::runtime_error("more Vulkan instances or devices alive at once than the plugin keeps tables for");
}

template <typename Table>
const Table* find(const std::array<Slot<Table>, kSlots>& slots, const void* key) {
    for (const Slot<Table>& slot : slots)
        if (slot.key.load(std::memory_order_acquire) == key) return &slot.table;
    return nullptr;
}

template <typename Function>
void load(Function& function, PFN_vkVoidFunction address) {
    function = reinterpret_cast<Function>(address);
}

}  // namespace

std::string openLoader() {
    static const std::string problem = [] {
        // Never closed: the loader keeps drivers and layers loaded for the process's lifetime.
        void* library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!library) return std::string("the Vulkan loader (libvulkan.so.1) cannot be loaded: ") + dlerror();
        load(gLoader.vkGetInstanceProcAddr, reinterpret_cast<PFN_vkVoidFunction>(dlsym(library, "vkGetInstanceProcAddr")));
        if (!gLoader.vkGetInstanceProcAddr) return std::string("the Vulkan loader has no vkGetInstanceProcAddr");
#define OBSCURA_VK_LOAD(name) load(gLoader.name, gLoader.vkGetInstanceProcAddr(VK_NULL_HANDLE, #name));
        OBSCURA_VK_LOADER_FUNCTIONS(OBSCURA_VK_LOAD)
#undef OBSCURA_VK_LOAD
        return std::string();
    }();
    return problem;
}

const LoaderTable& loader() {
    if (!gLoader.vkGetInstanceProcAddr) throw std::logic_error("Vulkan call before the loader was opened");
    return gLoader;
}

void addInstance(VkInstance instance) {
    std::lock_guard lock(gSlotsMutex);
    std::atomic<const void*>* published = nullptr;
    InstanceTable& table = claim(gInstances, published);
#define OBSCURA_VK_LOAD(name) load(table.name, gLoader.vkGetInstanceProcAddr(instance, #name));
    OBSCURA_VK_INSTANCE_FUNCTIONS(OBSCURA_VK_LOAD)
#undef OBSCURA_VK_LOAD
    published->store(dispatchKey(instance), std::memory_order_release);
}

void addDevice(VkInstance instance, VkDevice device) {
    std::lock_guard lock(gSlotsMutex);
    auto getDeviceProcAddr =
        reinterpret_cast<PFN_vkGetDeviceProcAddr>(gLoader.vkGetInstanceProcAddr(instance, "vkGetDeviceProcAddr"));
    std::atomic<const void*>* published = nullptr;
    DeviceTable& table = claim(gDevices, published);
#define OBSCURA_VK_LOAD(name) load(table.name, getDeviceProcAddr(device, #name));
    OBSCURA_VK_DEVICE_FUNCTIONS(OBSCURA_VK_LOAD)
#undef OBSCURA_VK_LOAD
    published->store(dispatchKey(device), std::memory_order_release);
}

void forget(const void* key) {
    std::lock_guard lock(gSlotsMutex);
    for (auto& slot : gInstances)
        if (slot.key.load(std::memory_order_relaxed) == key) slot.key.store(nullptr, std::memory_order_release);
    for (auto& slot : gDevices)
        if (slot.key.load(std::memory_order_relaxed) == key) slot.key.store(nullptr, std::memory_order_release);
}

const InstanceTable& instanceTable(const void* handle) {
    if (const InstanceTable* table = find(gInstances, dispatchKey(handle))) return *table;
    throw std::logic_error("Vulkan call on an instance the plugin did not create");
}

const DeviceTable& deviceTable(const void* handle) {
    if (const DeviceTable* table = find(gDevices, dispatchKey(handle))) return *table;
    throw std::logic_error("Vulkan call on a device the plugin did not create");
}

}  // namespace obscura::gpu::vk
