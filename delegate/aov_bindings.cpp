#include "delegate/aov_bindings.h"

#include "delegate/api_error.h"

#include <cstring>
#include <string>

namespace obscura::delegate {
namespace {

struct AovInfo {
    const char* name;
    passes::Aov aov;
    ObscuraFormat format;
};
constexpr AovInfo kAovs[] = {
    {"color", passes::Aov::Color, OBSCURA_FORMAT_FLOAT32_VEC4},
    {"depth", passes::Aov::Depth, OBSCURA_FORMAT_FLOAT32},
    {"normal", passes::Aov::Normal, OBSCURA_FORMAT_FLOAT32_VEC3},
    {"albedo", passes::Aov::Albedo, OBSCURA_FORMAT_FLOAT32_VEC3},
    {"primId", passes::Aov::PrimId, OBSCURA_FORMAT_INT32},
    {"instanceId", passes::Aov::InstanceId, OBSCURA_FORMAT_INT32},
    {"display", passes::Aov::Display, OBSCURA_FORMAT_UNORM8_VEC4},
    {"motion", passes::Aov::Motion, OBSCURA_FORMAT_FLOAT32_VEC3},
};

const char* formatName(ObscuraFormat f) {
    switch (f) {
        case OBSCURA_FORMAT_FLOAT32_VEC4: return "float32Vec4";
        case OBSCURA_FORMAT_FLOAT32_VEC3: return "float32Vec3";
        case OBSCURA_FORMAT_FLOAT32: return "float32";
        case OBSCURA_FORMAT_INT32: return "int32";
        case OBSCURA_FORMAT_UNORM8_VEC4: return "unorm8Vec4";
        default: return "unknown";
    }
}

const AovInfo& aovNamed(const char* name) {
    for (const auto& a : kAovs)
        if (std::strcmp(a.name, name) == 0) return a;
    throw ApiError{OBSCURA_ERROR_NOT_FOUND, std::string("unknown AOV '") + name + "'"};
}

}  // namespace

void refuseMappedBuffers(const ObscuraRenderPassDesc& desc, const RenderBufferLookup& find) {
    for (uint32_t i = 0; i < desc.aovBindingCount; ++i)
        if (const char* path = desc.aovBindings[i].renderBufferPath)
            if (const RenderBuffer* rb = find(path); rb && rb->mapped)
                throw ApiError{OBSCURA_ERROR_INVALID_STATE, std::string(path) + " is still mapped: unmap it before rendering"};
}

AovBindings bindAovs(const ObscuraRenderPassDesc& desc, const RenderBufferLookup& find, gpu::Device& device,
                     uint32_t maxImageSize) {
    AovBindings out;
    const RenderBuffer* firstSkippedBuffer = nullptr;
    out.width = desc.viewport[2] > 0 ? uint32_t(desc.viewport[2]) : 0;
    out.height = desc.viewport[3] > 0 ? uint32_t(desc.viewport[3]) : 0;
    for (uint32_t i = 0; i < desc.aovBindingCount; ++i) {
        const ObscuraAovBinding& b = desc.aovBindings[i];
        if (!b.aov || !b.renderBufferPath) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "AOV binding with NULL names"};
        const AovInfo& info = aovNamed(b.aov);
        RenderBuffer* rb = find(b.renderBufferPath);
        if (!rb) throw ApiError{OBSCURA_ERROR_NOT_FOUND, std::string("no render buffer at ") + b.renderBufferPath};
        // It keeps its last pixels, or stays unrendered; render returns BAD_PRIM_DATA.
        if (rb->skipped()) {
            if (!firstSkippedBuffer) firstSkippedBuffer = rb;
            continue;
        }
        if (rb->format() != info.format)
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, std::string("AOV '") + b.aov + "' needs format " +
                                                               formatName(info.format) + ", " + b.renderBufferPath +
                                                               " is " + formatName(rb->format())};
        if (out.width == 0) out.width = rb->width(), out.height = rb->height();
        if (rb->width() != out.width || rb->height() != out.height)
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, std::string(b.renderBufferPath) +
                                                               " does not match the viewport size"};
        out.requests.push_back({info.aov, rb->storage(device), rb->deviceStaging(device)});
        out.targets.push_back(rb);
    }
    if ((out.width == 0 || out.height == 0) && firstSkippedBuffer)
        throw ApiError{OBSCURA_ERROR_BAD_PRIM_DATA, "no size to render at: render buffer " + firstSkippedBuffer->problem()};
    if (out.width == 0 || out.height == 0)
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "empty viewport and no render buffers"};
    if (out.width > maxImageSize || out.height > maxImageSize)
        throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "viewport " + std::to_string(out.width) + "x" +
                                                           std::to_string(out.height) + " exceeds " +
                                                           std::to_string(maxImageSize) +
                                                           " pixels a side, the device's largest image"};
    return out;
}

}  // namespace obscura::delegate
