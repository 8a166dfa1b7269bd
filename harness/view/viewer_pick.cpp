// Picking, as usdview picks: the prim path under the cursor from the primId and instanceId AOVs
// (a PointInstancer's instance names its instancer and its index there, a native instance its
// instance proxy's path), and with ctrl the focus distance from the depth AOV.
#include "harness/view/viewer.h"

#include "harness/aov_output.h"
#include "schemas/camera_depth.h"

#include <cstdio>
#include <cstring>

namespace obscura::harness::view {

void Viewer::pick(double x, double y, bool focus) {
    const int px = int(x), py = int(y);
    if (px < 0 || py < 0 || px >= width_ || py >= height_) return;
    if (!render(true)) return;
    const ObscuraApiV1& api = session_.api();
    auto read = [&](const char* aov) {
        ObscuraMappedBuffer m{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(m)};
        uint32_t word = 0;
        if (api.mapRenderBuffer(session_.delegate(), buffers_[aov].c_str(), &m) == OBSCURA_OK)
            std::memcpy(&word, static_cast<const char*>(m.data) + size_t(py) * m.rowStride + size_t(px) * 4, 4);
        api.unmapRenderBuffer(session_.delegate(), buffers_[aov].c_str());
        return word;
    };
    const int32_t primId = int32_t(read("primId")), instanceId = int32_t(read("instanceId"));
    const uint32_t depthBits = read("depth");
    float depth = 0;
    std::memcpy(&depth, &depthBits, 4);
    std::string path;
    for (const auto& [prim, type] : session_.host().insertedPrims()) {
        int32_t id = -1;
        if (api.getPrimId(session_.delegate(), prim.c_str(), &id) == OBSCURA_OK && id == primId) path = prim;
    }
    // A native instance is named by its instance proxy's path, a PointInstancer's by the instancer.
    const std::string proxy = instanceId >= 0 ? session_.host().instanceProxyPath(path, instanceId) : std::string();
    const std::string instancer = instanceId >= 0 ? session_.host().instancerOf(path) : std::string();
    picked_ = path.empty()        ? "nothing"
              : !proxy.empty()    ? proxy
              : instancer.empty() ? path
                                  : instancer + " instance " + std::to_string(instanceId) + " (" + path + ")";
    std::printf("pick %d %d: %s\n", px, py, picked_.c_str());
    std::fflush(stdout);
    if (focus && !path.empty()) {
        useFreeCamera();
        const schema::CameraDepth camera{false, scene_.lens.nearClip, scene_.lens.farClip};
        scene_.lens.focusDistance = schema::viewDistance(depth, camera);
        std::printf("focus distance: %g\n", scene_.lens.focusDistance);
        cameraChanged();
    }
}

}  // namespace obscura::harness::view
