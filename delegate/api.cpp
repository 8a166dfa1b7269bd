// The C ABI entry points (include/obscura/obscura.h). Every entry point runs inside a catch
// ladder (after OpenFX): no exception crosses the boundary, every failure becomes a status and
// a message the host reads with lastError.
#include "delegate/render_delegate.h"
#include "renderer/render_settings.h"
#include "gpu/context.h"
#include "gpu/vk_check.h"

#include <obscura/obscura.h>

#include <atomic>
#include <cstring>
#include <new>
#include <thread>

struct ObscuraDelegate_T {
    std::unique_ptr<obscura::delegate::RenderDelegate> impl;
    // The thread inside a call on this delegate (default: none). Calls are serialised by the host;
    // one made while another runs (from a scene-delegate or log callback, or another thread) is
    // refused, never run on a delegate in the middle of a call.
    std::atomic<std::thread::id> inCall{};
};

namespace {

using obscura::delegate::ApiError;
using obscura::delegate::RenderDelegate;

// Errors of calls that have no delegate (creation, enumeration, null handles).
thread_local std::string tlsLastError;

template <typename F>
ObscuraStatus guarded(std::string* errorSink, F&& body) {
    std::string& sink = errorSink ? *errorSink : tlsLastError;
    try {
        // Success leaves the message of the last failure in place (errno-like), so a host may
        // read it after further calls.
        return body();
    } catch (const ApiError& e) {
        sink = e.message;
        return e.status;
    } catch (const obscura::gpu::DeviceError& e) {
        sink = e.what();
        return e.outOfMemory() ? OBSCURA_ERROR_OUT_OF_MEMORY : OBSCURA_ERROR_DEVICE;
    } catch (const std::bad_alloc&) {
        sink = "out of memory";
        return OBSCURA_ERROR_OUT_OF_MEMORY;
    } catch (const std::exception& e) {
        sink = std::string("internal error: ") + e.what();
        return OBSCURA_ERROR_INTERNAL;
    } catch (...) {
        sink = "internal error: unknown exception";
        return OBSCURA_ERROR_INTERNAL;
    }
}

// Marks `d` as in a call for the lifetime of the guard, unless a call on it is already running.
class CallGuard {
public:
    explicit CallGuard(ObscuraDelegate d) : d_(d) {
        std::thread::id none{};
        entered_ = d_->inCall.compare_exchange_strong(none, std::this_thread::get_id());
        reentrant_ = !entered_ && none == std::this_thread::get_id();
    }
    ~CallGuard() {
        if (entered_) d_->inCall.store(std::thread::id{});
    }
    bool entered() const { return entered_; }
    // The refused call came from inside a call on this thread (a callback), not from another thread.
    bool reentrant() const { return reentrant_; }

private:
    ObscuraDelegate d_;
    bool entered_ = false;
    bool reentrant_ = false;
};

ObscuraStatus refuseConcurrentCall(const CallGuard& guard, ObscuraDelegate d, const char* function) {
    std::string message = std::string(function) +
                          (guard.reentrant() ? " called from a callback while a call on the same delegate runs"
                                             : " called while another thread is in a call on the same delegate") +
                          ": calls on one delegate must be serialised, so it was refused and changed nothing";
    // From a callback the host reads lastError(delegate) on the same thread; from another thread the
    // delegate's message belongs to the running call, so this one goes to lastError(NULL).
    if (guard.reentrant()) d->impl->lastError() = message;
    else tlsLastError = message;
    return OBSCURA_ERROR_INVALID_STATE;
}

// Runs `body` on a valid delegate; null handles are refused with a message, calls made while
// another call on the delegate runs with OBSCURA_ERROR_INVALID_STATE.
template <typename F>
ObscuraStatus withDelegate(ObscuraDelegate d, const char* function, F&& body) {
    if (!d || !d->impl) {
        tlsLastError = "null delegate handle";
        return OBSCURA_ERROR_INVALID_ARGUMENT;
    }
    CallGuard guard(d);
    if (!guard.entered()) return refuseConcurrentCall(guard, d, function);
    return guarded(&d->impl->lastError(), [&] { return body(*d->impl); });
}

std::string requireString(const char* s, const char* what) {
    if (!s) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, std::string(what) + " is NULL"};
    return s;
}

ObscuraStatus createDelegate(const ObscuraDelegateCreateInfo* info, ObscuraDelegate* out) {
    return guarded(nullptr, [&] {
        if (!out) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "outDelegate is NULL"};
        *out = nullptr;
        ObscuraDelegateCreateInfo defaults{OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO, nullptr,
                                           sizeof(ObscuraDelegateCreateInfo), nullptr, -1, nullptr, nullptr};
        if (info && (info->sType != OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO ||
                     info->structSize < sizeof(ObscuraDelegateCreateInfo)))
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "ObscuraDelegateCreateInfo: wrong sType or structSize"};
        auto handle = std::make_unique<ObscuraDelegate_T>();
        handle->impl = std::make_unique<RenderDelegate>(info ? *info : defaults);
        *out = handle.release();
        return OBSCURA_OK;
    });
}

ObscuraStatus destroyDelegate(ObscuraDelegate d) {
    if (d) {
        CallGuard guard(d);
        if (!guard.entered()) return refuseConcurrentCall(guard, d, "destroyDelegate");
    }
    return guarded(nullptr, [&] {
        delete d;
        return OBSCURA_OK;
    });
}

const char* lastError(ObscuraDelegate d) {
    if (d && d->impl) return d->impl->lastError().c_str();
    return tlsLastError.c_str();
}

ObscuraStatus setSceneDelegate(ObscuraDelegate d, const ObscuraSceneDelegate* sd) {
    return withDelegate(d, "setSceneDelegate", [&](RenderDelegate& r) {
        if (!sd) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "sceneDelegate is NULL"};
        r.setSceneDelegate(*sd);
        return OBSCURA_OK;
    });
}

ObscuraStatus insertPrim(ObscuraDelegate d, const char* type, const char* path) {
    return withDelegate(d, "insertPrim", [&](RenderDelegate& r) {
        r.insertPrim(requireString(type, "type"), requireString(path, "path"));
        return OBSCURA_OK;
    });
}

ObscuraStatus removePrim(ObscuraDelegate d, const char* path) {
    return withDelegate(d, "removePrim", [&](RenderDelegate& r) {
        r.removePrim(requireString(path, "path"));
        return OBSCURA_OK;
    });
}

ObscuraStatus markDirty(ObscuraDelegate d, const char* path, ObscuraDirtyBits bits) {
    return withDelegate(d, "markDirty", [&](RenderDelegate& r) {
        r.markDirty(requireString(path, "path"), bits);
        return OBSCURA_OK;
    });
}

ObscuraStatus setRenderSetting(ObscuraDelegate d, const char* key, const ObscuraValue* value) {
    return withDelegate(d, "setRenderSetting", [&](RenderDelegate& r) {
        r.setRenderSetting(requireString(key, "key"), value);
        return OBSCURA_OK;
    });
}

ObscuraStatus render(ObscuraDelegate d, const ObscuraRenderPassDesc* desc) {
    return withDelegate(d, "render", [&](RenderDelegate& r) {
        if (!desc) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "render pass description is NULL"};
        try {
            return r.render(*desc);
        } catch (const obscura::gpu::DeviceError& e) {
            // A lost device stays lost: later renders are refused until the host makes a new delegate.
            if (e.deviceLost()) r.deviceLost(e.what());
            throw;
        }
    });
}

ObscuraStatus mapRenderBuffer(ObscuraDelegate d, const char* path, ObscuraMappedBuffer* out) {
    return withDelegate(d, "mapRenderBuffer", [&](RenderDelegate& r) {
        if (!out || out->structSize < sizeof(ObscuraMappedBuffer))
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "ObscuraMappedBuffer is NULL or too small"};
        r.map(requireString(path, "path"), *out);
        return OBSCURA_OK;
    });
}

ObscuraStatus exportRenderBuffer(ObscuraDelegate d, const char* path, ObscuraExternalBuffer* out) {
    return withDelegate(d, "exportRenderBuffer", [&](RenderDelegate& r) {
        if (!out || out->structSize < sizeof(ObscuraExternalBuffer))
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "ObscuraExternalBuffer is NULL or too small"};
        r.exportBuffer(requireString(path, "path"), *out);
        return OBSCURA_OK;
    });
}

ObscuraStatus unmapRenderBuffer(ObscuraDelegate d, const char* path) {
    return withDelegate(d, "unmapRenderBuffer", [&](RenderDelegate& r) {
        r.unmap(requireString(path, "path"));
        return OBSCURA_OK;
    });
}

ObscuraStatus getPassTimings(ObscuraDelegate d, ObscuraPassTiming* timings, uint32_t* count) {
    return withDelegate(d, "getPassTimings", [&](RenderDelegate& r) {
        if (!count) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "count is NULL"};
        const auto& t = r.passTimings();
        if (!timings) {
            *count = static_cast<uint32_t>(t.size());
            return OBSCURA_OK;
        }
        uint32_t n = std::min<uint32_t>(*count, static_cast<uint32_t>(t.size()));
        for (uint32_t i = 0; i < n; ++i) {
            timings[i].sType = OBSCURA_STRUCTURE_TYPE_PASS_TIMING;
            timings[i].pNext = nullptr;
            timings[i].structSize = sizeof(ObscuraPassTiming);
            std::snprintf(timings[i].pass, sizeof(timings[i].pass), "%s", t[i].pass.c_str());
            timings[i].milliseconds = t[i].milliseconds;
        }
        *count = n;
        return OBSCURA_OK;
    });
}

ObscuraStatus getRenderStats(ObscuraDelegate d, ObscuraRenderStats* out) {
    return withDelegate(d, "getRenderStats", [&](RenderDelegate& r) {
        if (!out || out->structSize < sizeof(ObscuraRenderStats))
            throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "ObscuraRenderStats is NULL or too small"};
        r.stats(*out);
        return OBSCURA_OK;
    });
}

ObscuraStatus enumerateDevices(ObscuraDeviceInfo* devices, uint32_t* count) {
    return guarded(nullptr, [&] {
        if (!count) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "count is NULL"};
        auto list = obscura::gpu::Context::enumerate();
        if (!list) throw ApiError{OBSCURA_ERROR_DEVICE, list.error()};
        if (!devices) {
            *count = static_cast<uint32_t>(list->size());
            return OBSCURA_OK;
        }
        uint32_t n = std::min<uint32_t>(*count, static_cast<uint32_t>(list->size()));
        for (uint32_t i = 0; i < n; ++i) {
            const auto& s = (*list)[i];
            ObscuraDeviceInfo& o = devices[i];
            o.sType = OBSCURA_STRUCTURE_TYPE_DEVICE_INFO;
            o.pNext = nullptr;
            o.structSize = sizeof(ObscuraDeviceInfo);
            std::snprintf(o.name, sizeof(o.name), "%s", s.name.c_str());
            std::snprintf(o.driver, sizeof(o.driver), "%s", s.driver.c_str());
            o.apiVersion = s.apiVersion;
            o.isDiscrete = s.discrete;
            o.isCpu = s.cpu;
            uint32_t maxSamples = 1;
            for (uint32_t b = 1; b <= 64; b <<= 1)
                if (s.msaaSamples & b) maxSamples = b;
            o.maxMsaaSamples = maxSamples;
        }
        *count = n;
        return OBSCURA_OK;
    });
}

ObscuraStatus getPrimId(ObscuraDelegate d, const char* path, int32_t* outId) {
    return withDelegate(d, "getPrimId", [&](RenderDelegate& r) {
        if (!outId) throw ApiError{OBSCURA_ERROR_INVALID_ARGUMENT, "outId is NULL"};
        *outId = r.primId(requireString(path, "path"));
        return OBSCURA_OK;
    });
}

ObscuraStatus describeRenderSetting(uint32_t index, const char** name, const char** description) {
    const auto* info = obscura::renderer::renderSettingAt(index);
    if (!info) return OBSCURA_ERROR_NOT_FOUND;
    if (name) *name = info->name;
    if (description) *description = info->description;
    return OBSCURA_OK;
}

// One table for every 1.x request: 1.0's functions first, then 1.2's (the header's ObscuraApiV1_2).
const ObscuraApiV1_2 kApiV1 = {
    {
        sizeof(ObscuraApiV1_2), OBSCURA_ABI_VERSION_MAJOR, OBSCURA_ABI_VERSION_MINOR,
        createDelegate,         destroyDelegate,           lastError,
        setSceneDelegate,       insertPrim,                removePrim,
        markDirty,              setRenderSetting,          render,
        mapRenderBuffer,        unmapRenderBuffer,         getPassTimings,
        getRenderStats,         enumerateDevices,          getPrimId,
        describeRenderSetting,
    },
    exportRenderBuffer,
};

}  // namespace

extern "C" OBSCURA_EXPORT ObscuraStatus obscuraGetApi(uint32_t versionMajor, uint32_t versionMinor, const void** outTable) {
    if (!outTable) return OBSCURA_ERROR_INVALID_ARGUMENT;
    *outTable = nullptr;
    if (versionMajor != OBSCURA_ABI_VERSION_MAJOR || versionMinor > OBSCURA_ABI_VERSION_MINOR) {
        tlsLastError = "ABI " + std::to_string(versionMajor) + "." + std::to_string(versionMinor) +
                       " requested; this plugin provides " + std::to_string(OBSCURA_ABI_VERSION_MAJOR) + "." +
                       std::to_string(OBSCURA_ABI_VERSION_MINOR);
        return OBSCURA_ERROR_UNSUPPORTED_VERSION;
    }
    *outTable = &kApiV1;
    return OBSCURA_OK;
}
