#include "passes/hi_z.h"

#include "generated/shader_layouts.h"
#include "passes/shader_pass.h"

#include <algorithm>
#include <array>

namespace obscura::passes {
namespace {

// Levels 1 to 5 come from shaders/hi_z.comp (a 32x32-pixel tile per workgroup), the rest from
// shaders/hi_z_top.comp.
constexpr uint32_t kLevelsPerTile = 5;

// Mirrors shaders/common/hi_z.glsl.
uint32_t levelSide(uint32_t pixels, uint32_t level) { return (pixels + (1u << level) - 1u) >> level; }
uint32_t topLevel(uint32_t width, uint32_t height) {
    uint32_t level = 1;
    while (levelSide(width, level) > 1 || levelSide(height, level) > 1) ++level;
    return level;
}

// Mirrors the push constants of shaders/hi_z.comp and shaders/hi_z_top.comp.
struct TilePush {
    std::array<uint32_t, 2> pixels;
    uint32_t samples;
};
OBSCURA_SHADER_OFFSET(TilePush, hi_z_comp::Push, pixels);
OBSCURA_SHADER_OFFSET(TilePush, hi_z_comp::Push, samples);
struct TopPush {
    std::array<uint32_t, 2> pixels;
};
OBSCURA_SHADER_OFFSET(TopPush, hi_z_top_comp::Push, pixels);

}  // namespace

uint64_t hiZPyramidFloats(uint32_t width, uint32_t height) {
    uint64_t floats = 0;
    for (uint32_t level = 1; level <= topLevel(width, height); ++level)
        floats += uint64_t(levelSide(width, level)) * levelSide(height, level);
    return floats;
}

gpu::BufferHandle addHiZPasses(gpu::FrameGraph& graph, gpu::ImageHandle depth, gpu::BufferHandle pyramid,
                               const std::string& label) {
    const gpu::ImageDesc& desc = graph.imageDesc(depth);
    const bool multisampled = desc.samples != VK_SAMPLE_COUNT_1_BIT;
    ComputePass tiles{multisampled ? "hi_z_multisampled" : "hi_z", {sampled(depth), bufferWrite(pyramid)},
                      bytesOf(TilePush{{desc.width, desc.height}, uint32_t(desc.samples)})};
    // One invocation per texel of level 1, a 16x16 group per 32x32 pixels.
    tiles.texels = std::array<uint32_t, 2>{levelSide(desc.width, 1), levelSide(desc.height, 1)};
    tiles.texelsPerGroup = {16, 16};
    tiles.label = label;
    pyramid = addComputePass(graph, std::move(tiles)).buffers[0];
    if (topLevel(desc.width, desc.height) <= kLevelsPerTile) return pyramid;
    ComputePass top{"hi_z_top", {bufferReadWrite(pyramid)}, bytesOf(TopPush{{desc.width, desc.height}})};
    top.texels = std::array<uint32_t, 2>{1, 1};  // one workgroup
    top.texelsPerGroup = {1, 1};
    top.label = label + "_top";
    return addComputePass(graph, std::move(top)).buffers[0];
}

}  // namespace obscura::passes
