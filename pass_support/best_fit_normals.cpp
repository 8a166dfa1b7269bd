#include "pass_support/best_fit_normals.h"

#include <algorithm>
#include <cmath>

namespace obscura::passes {

// generated/best_fit_normals_table.cpp
extern const uint16_t kBestFitScaleTable[kBestFitTableSize * kBestFitTableSize];

namespace {

std::array<float, 2> tableCoordinates(const std::array<float, 3>& n) {
    std::array<float, 3> un = {std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])};
    float maxAbs = std::max(un[2], std::max(un[0], un[1]));
    std::array<float, 2> uv;
    if (un[2] < maxAbs) uv = un[1] < maxAbs ? std::array<float, 2>{un[1], un[2]} : std::array<float, 2>{un[0], un[2]};
    else uv = {un[0], un[1]};
    if (uv[0] < uv[1]) std::swap(uv[0], uv[1]);
    uv[1] /= std::max(uv[0], 1e-8f);
    return uv;
}

}  // namespace

std::span<const uint16_t> bestFitScaleTable() {
    return {kBestFitScaleTable, size_t(kBestFitTableSize) * kBestFitTableSize};
}

std::array<uint8_t, 3> encodeBestFitNormal(const std::array<float, 3>& normalIn) {
    float len = std::sqrt(normalIn[0] * normalIn[0] + normalIn[1] * normalIn[1] + normalIn[2] * normalIn[2]);
    std::array<float, 3> n = {normalIn[0] / len, normalIn[1] / len, normalIn[2] / len};
    auto uv = tableCoordinates(n);
    // Nearest texel, as the G-buffer pass samples it.
    auto texel = [](float c) {
        return std::min(kBestFitTableSize - 1, uint32_t(std::max(0.0f, c) * float(kBestFitTableSize)));
    };
    float scale = float(bestFitScaleTable()[size_t(texel(uv[1])) * kBestFitTableSize + texel(uv[0])]) / 65535.0f;
    float maxAbs = std::max(std::fabs(n[2]), std::max(std::fabs(n[0]), std::fabs(n[1])));
    std::array<uint8_t, 3> out;
    for (int c = 0; c < 3; ++c) {
        float v = n[c] / maxAbs * scale * 0.5f + 0.5f;
        out[c] = uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    }
    return out;
}

std::array<uint8_t, 3> encodeNormalizedNormal(const std::array<float, 3>& n) {
    std::array<uint8_t, 3> out;
    for (int c = 0; c < 3; ++c) out[c] = uint8_t(std::lround(std::clamp(n[c] * 0.5f + 0.5f, 0.0f, 1.0f) * 255.0f));
    return out;
}

std::array<float, 3> decodeNormal(const std::array<uint8_t, 3>& s) {
    std::array<float, 3> n;
    for (int c = 0; c < 3; ++c) n[c] = float(s[c]) / 255.0f * 2.0f - 1.0f;
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (auto& c : n) c /= std::max(len, 1e-12f);
    return n;
}

gpu::ImagePtr createBestFitNormalsTexture(gpu::FrameBackend& backend) {
    std::span<const uint16_t> table = bestFitScaleTable();
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_R16_UNORM;
    desc.width = desc.height = kBestFitTableSize;
    return backend.createTexture(desc, table.data(), table.size() * sizeof(uint16_t), "best-fit normals");
}

}  // namespace obscura::passes
