#include "pass_support/best_fit_normals.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <thread>

namespace obscura::passes {
namespace {

// Appendix A, quantize255: the value an 8-bit UNORM channel reconstructs for c in [-1, 1].
float quantize255(float c) {
    float w = std::clamp(c * 0.5f + 0.5f, 0.0f, 1.0f);
    float r = std::round(w * 255.0f);
    return r / 255.0f * 2.0f - 1.0f;
}

// The direction a table texel stands for: z is the major axis, x the larger minor component.
std::array<float, 3> texelDirection(uint32_t i, uint32_t j) {
    float u = (float(i) + 0.5f) / float(kBestFitTableSize);
    float v = (float(j) + 0.5f) / float(kBestFitTableSize);
    // Texels beyond the region where z stays the major axis are never looked up; clamp them to
    // its edge so the table stays smooth there.
    u = std::min(u, 1.0f / std::sqrt(2.0f + v * v));
    float a = u, b = u * v;
    float m = std::sqrt(std::max(0.0f, 1.0f - a * a - b * b));
    return {a, b, m};
}

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

float findBestFitScale(const std::array<float, 3>& direction) {
    float maxAbs = std::max(std::fabs(direction[2]), std::max(std::fabs(direction[0]), std::fabs(direction[1])));
    std::array<float, 3> n = {direction[0] / maxAbs, direction[1] / maxAbs, direction[2] / maxAbs};
    float minError = 100000.0f;
    float bestScale = 1.0f;
    for (float step = 1.5f; step <= 127.5f; step += 1.0f) {
        float t = step / 127.5f;
        float error = 0.0f;
        for (int c = 0; c < 3; ++c) {
            float probe = n[c] * t;
            error = std::max(error, std::fabs((quantize255(probe) - probe) / t));
        }
        if (error < minError) {
            minError = error;
            bestScale = t;
        }
    }
    return bestScale;
}

const std::vector<uint16_t>& bestFitScaleTable() {
    static std::vector<uint16_t> table;
    static std::once_flag once;
    std::call_once(once, [] {
        table.resize(size_t(kBestFitTableSize) * kBestFitTableSize);
        unsigned workers = std::max(1u, std::thread::hardware_concurrency());
        std::vector<std::thread> threads;
        for (unsigned w = 0; w < workers; ++w) {
            threads.emplace_back([w, workers] {
                for (uint32_t j = w; j < kBestFitTableSize; j += workers)
                    for (uint32_t i = 0; i < kBestFitTableSize; ++i) {
                        float scale = findBestFitScale(texelDirection(i, j));
                        table[size_t(j) * kBestFitTableSize + i] = uint16_t(std::lround(scale * 65535.0f));
                    }
            });
        }
        for (auto& t : threads) t.join();
    });
    return table;
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
    const auto& table = bestFitScaleTable();
    gpu::ImageDesc desc;
    desc.format = VK_FORMAT_R16_UNORM;
    desc.width = desc.height = kBestFitTableSize;
    return backend.createTexture(desc, table.data(), table.size() * sizeof(uint16_t), "best-fit normals");
}

}  // namespace obscura::passes
