#include "gpu/pipeline_disk_cache.h"

#include "gpu/content_hash.h"
#include "gpu/context.h"
#include "gpu/replace_file.h"
#include "gpu/vk_check.h"

#include <cstdio>
#include <cstring>
#include <vector>

namespace obscura::gpu {

namespace {

// What precedes the driver's data in the file: enough to know it is whole and unchanged.
struct FileHeader {
    char magic[8];
    uint64_t dataSize;
    uint64_t dataHash;
};
constexpr char kMagic[8] = {'O', 'B', 'S', 'C', 'P', 'L', 'C', '1'};

std::string hex(const uint8_t* bytes, size_t count) {
    std::string text;
    char digits[3];
    for (size_t i = 0; i < count; ++i) {
        std::snprintf(digits, sizeof(digits), "%02x", bytes[i]);
        text += digits;
    }
    return text;
}

// Why `data` cannot seed this device's cache, or empty when it can (the Vulkan spec's
// VkPipelineCacheHeaderVersionOne, which every driver writes first).
std::string incompatibility(const std::vector<char>& file, const VkPhysicalDeviceProperties& properties) {
    if (file.size() < sizeof(FileHeader)) return "shorter than its header";
    FileHeader header;
    std::memcpy(&header, file.data(), sizeof(header));
    if (std::memcmp(header.magic, kMagic, sizeof(kMagic)) != 0) return "not a pipeline cache of this renderer";
    if (header.dataSize != file.size() - sizeof(FileHeader)) return "truncated";
    const char* data = file.data() + sizeof(FileHeader);
    if (hashBytes(data, header.dataSize) != header.dataHash) return "corrupt (its hash differs)";
    VkPipelineCacheHeaderVersionOne vulkan;
    if (header.dataSize < sizeof(vulkan)) return "shorter than a Vulkan pipeline cache header";
    std::memcpy(&vulkan, data, sizeof(vulkan));
    if (vulkan.headerVersion != VK_PIPELINE_CACHE_HEADER_VERSION_ONE || vulkan.vendorID != properties.vendorID ||
        vulkan.deviceID != properties.deviceID ||
        std::memcmp(vulkan.pipelineCacheUUID, properties.pipelineCacheUUID, VK_UUID_SIZE) != 0)
        return "written by another device or driver";
    return {};
}

}  // namespace

PipelineDiskCache::PipelineDiskCache(const Context& context, std::optional<std::filesystem::path> folder)
    : device_(context.device()) {
    const VkPhysicalDeviceProperties& properties = context.properties();
    std::vector<char> file;
    if (folder) {
        char name[64];
        std::snprintf(name, sizeof(name), "pipelines-%04x-%04x-", properties.vendorID, properties.deviceID);
        file_ = *folder / (name + hex(properties.pipelineCacheUUID, VK_UUID_SIZE) + ".bin");
        if (auto bytes = readWholeFile(*file_)) file = std::move(*bytes);
    }
    VkPipelineCacheCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    if (!file.empty()) {
        const std::string problem = incompatibility(file, properties);
        if (problem.empty()) {
            ci.initialDataSize = file.size() - sizeof(FileHeader);
            ci.pInitialData = file.data() + sizeof(FileHeader);
            loadedBytes_ = ci.initialDataSize;
        } else {
            context.log(LogLevel::Info, "pipeline cache " + file_->string() + " ignored: " + problem);
        }
    }
    vkCheck(vkCreatePipelineCache(device_, &ci, nullptr, &cache_), "vkCreatePipelineCache");
}

PipelineDiskCache::~PipelineDiskCache() {
    save();
    vkDestroyPipelineCache(device_, cache_, nullptr);
}

void PipelineDiskCache::save() {
    if (!file_) return;
    size_t size = 0;
    if (vkGetPipelineCacheData(device_, cache_, &size, nullptr) != VK_SUCCESS || size <= loadedBytes_) return;
    std::vector<char> bytes(sizeof(FileHeader) + size);
    if (vkGetPipelineCacheData(device_, cache_, &size, bytes.data() + sizeof(FileHeader)) != VK_SUCCESS) return;
    bytes.resize(sizeof(FileHeader) + size);
    FileHeader header{};
    std::memcpy(header.magic, kMagic, sizeof(kMagic));
    header.dataSize = size;
    header.dataHash = hashBytes(bytes.data() + sizeof(FileHeader), size);
    std::memcpy(bytes.data(), &header, sizeof(header));

    if (!replaceFile(*file_, bytes.data(), bytes.size())) return;
    loadedBytes_ = size;
}

}  // namespace obscura::gpu
