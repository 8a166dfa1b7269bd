// Occlusion culling from frame to frame (seed 004 "Occlusion culling", render setting
// occlusionCulling): each frame's coverage buffer is written into a host-visible buffer, and the
// next frame, once the last one's fence has passed (the talk's one frame of latency: the CPU never
// waits on the frame it is building), reprojects it into its own view (renderer/coverage_buffer.h).
// The history stands only while what the last frame drew stands: another camera (a cut), size,
// time code, drawn prim or setting starts afresh, and that frame draws everything.
#pragma once

#include "gpu/frame_backend.h"
#include "gpu/frame_graph.h"
#include "renderer/coverage_buffer.h"

#include <optional>
#include <string>

namespace obscura::renderer {

// What a coverage buffer depends on besides the view.
struct CoverageKey {
    std::string camera;             // FrameCamera::key
    double time = 0.0;              // the frame's time code
    uint64_t drawnVersion = 0;      // FrameRequest::drawnVersion
    uint64_t settingsVersion = 0;   // FrameRequest::settingsVersion
    bool operator==(const CoverageKey&) const = default;
};

class OcclusionHistory {
public:
    explicit OcclusionHistory(gpu::FrameBackend& backend) : backend_(backend) {}

    // First in a frame that culls: the last frame's coverage reprojected into `current`, or none
    // where it does not stand for this frame.
    std::optional<CoverageBuffer> reproject(const CoverageKey& key, const CoverageView& current);
    // Adds the coverage pass reducing `depth` (seen through `view`) into the history's buffer; the
    // history holds it once the frame is done (frameDone).
    void addToFrame(gpu::FrameGraph& graph, gpu::ImageHandle depth, const CoverageKey& key, const CoverageView& view);
    // After the frame ran: its coverage buffer, if it added one, is the next frame's history.
    void frameDone();

private:
    struct Seen {
        CoverageKey key;
        CoverageView view;
    };
    gpu::FrameBackend& backend_;
    gpu::BufferPtr tiles_;       // host-visible, CoverageGrid::bytes() of the last size
    std::optional<Seen> valid_;  // what tiles_ holds, once written
    std::optional<Seen> pending_;  // what the frame being built writes into it
};

}  // namespace obscura::renderer
