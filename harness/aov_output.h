// Writes mapped AOVs to files: every AOV as linear channels of one OpenEXR (colour as R,G,B,A,
// depth as Z holding linear distance along the view axis, others as named layers), or the
// display-referred colour as PNG.
#pragma once

#include <obscura/obscura.h>

#include <string>
#include <vector>

namespace obscura::harness {

struct MappedAov {
    std::string aov;
    ObscuraMappedBuffer buffer;
};

// Camera facts needed to turn Hydra's clip-space depth into the EXR's linear Z.
struct DepthConversion {
    bool orthographic = false;
    double nearClip = 1.0;
    double farClip = 1000000.0;
};

// Linear distance along the view axis for a clip-space depth in [0,1]; +inf where nothing drew.
double linearDepth(float clipDepth, const DepthConversion& camera);

std::string writeExrAovs(const std::string& path, const std::vector<MappedAov>& aovs, const DepthConversion& camera);
std::string writePngDisplay(const std::string& path, const ObscuraMappedBuffer& display);

}  // namespace obscura::harness
