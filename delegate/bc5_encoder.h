// BC5 (3Dc) compression of tangent-space normal maps (Kaplanyan 2010, slides "Normal maps
// precision" and "3Dc encoder improvements"). A BC5 block holds 4x4 texels of two channels, each
// a BC4 block: two 8-bit endpoints and a 3-bit index per texel into the eight values between them.
// x and y are stored as x = 0.5 n.x + 0.5 (the usual unsigned normal-map encoding) and the shader
// reconstructs z = sqrt(1 - x^2 - y^2). Pure CPU code.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace obscura::delegate {

// Unit reference normals of one image, rows top first.
struct NormalImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<std::array<float, 3>> normals;
};

enum class Bc5Encoder {
    // The common encoder: each channel a BC4 block on its own, endpoints at the channel's
    // extremes, each index the nearest value of its channel.
    PerChannel,
    // The talk's improvement: endpoints and index pairs chosen to minimise the angle between the
    // reconstructed normal (z from x and y, normalised) and the reference, starting from the
    // common encoder's block and searching its endpoints, never raising the block's largest angle
    // above the common encoding's. As the talk's "adaptive approach", only blocks whose common
    // encoding errs by more than a threshold angle are searched.
    NormalAware,
};

// 16 bytes per 4x4 block (BC5_UNORM: the x block, then the y block), blocks in rows; texels past
// the image's edge repeat its last row and column.
std::vector<std::byte> encodeBc5(const NormalImage& image, Bc5Encoder encoder);

// The unit normal each texel decodes to, as the shader reconstructs it.
NormalImage decodeBc5(const std::vector<std::byte>& blocks, uint32_t width, uint32_t height);

struct AngularError {
    double meanDegrees = 0.0;
    double maxDegrees = 0.0;
};
AngularError angularError(const NormalImage& reference, const NormalImage& decoded);

// The unit normal stored as (x, y) in [0, 1]: z = sqrt(1 - nx^2 - ny^2), 0 past the unit circle.
std::array<float, 3> reconstructNormal(float x, float y);

}  // namespace obscura::delegate
