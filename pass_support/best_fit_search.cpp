#include "pass_support/best_fit_search.h"

#include <algorithm>
#include <cmath>
#include <thread>

namespace obscura::passes {
namespace {

// Appendix A, quantize255: the value an 8-bit UNORM channel reconstructs for c in [-1, 1].
float quantize255(float c) {
    float w = std::clamp(c * 0.5f + 0.5f, 0.0f, 1.0f);
    float r = std::round(w * 255.0f);
    return r / 255.0f * 2.0f - 1.0f;
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

std::array<float, 3> bestFitTexelDirection(uint32_t i, uint32_t j) {
    float u = (float(i) + 0.5f) / float(kBestFitTableSize);
    float v = (float(j) + 0.5f) / float(kBestFitTableSize);
    // Texels beyond the region where z stays the major axis are never looked up; clamp them to
    // its edge so the table stays smooth there.
    u = std::min(u, 1.0f / std::sqrt(2.0f + v * v));
    float a = u, b = u * v;
    float m = std::sqrt(std::max(0.0f, 1.0f - a * a - b * b));
    return {a, b, m};
}

uint16_t bestFitTableEntry(uint32_t i, uint32_t j) {
    return uint16_t(std::lround(findBestFitScale(bestFitTexelDirection(i, j)) * 65535.0f));
}

std::vector<uint16_t> computeBestFitScaleTable() {
    std::vector<uint16_t> table(size_t(kBestFitTableSize) * kBestFitTableSize);
    unsigned workers = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> threads;
    for (unsigned w = 0; w < workers; ++w)
        threads.emplace_back([&table, w, workers] {
            for (uint32_t j = w; j < kBestFitTableSize; j += workers)
                for (uint32_t i = 0; i < kBestFitTableSize; ++i)
                    table[size_t(j) * kBestFitTableSize + i] = bestFitTableEntry(i, j);
        });
    for (auto& t : threads) t.join();
    return table;
}

}  // namespace obscura::passes
