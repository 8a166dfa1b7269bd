// Writes mapped AOVs to files: every AOV as linear channels of one OpenEXR (colour as R,G,B,A,
// depth as Z holding linear distance along the view axis, others as named layers), or the
// display-referred colour as PNG.
#pragma once

#include "schemas/camera_depth.h"

#include <obscura/obscura.h>

#include <string>
#include <vector>

namespace obscura::harness {

struct MappedAov {
    std::string aov;
    ObscuraMappedBuffer buffer;
};

// `camera`: the rendering camera's projection and clipping range, which turn the depth AOV into the
// EXR's linear Z (schemas/camera_depth.h).
std::string writeExrAovs(const std::string& path, const std::vector<MappedAov>& aovs,
                         const schema::CameraDepth& camera);
std::string writePngDisplay(const std::string& path, const ObscuraMappedBuffer& display);

}  // namespace obscura::harness
