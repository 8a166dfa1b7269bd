// The texture feeding one UsdPreviewSurface input, as the host flattened its UsdUVTexture into
// the material's obscura:<input>:* attributes (schemas/material.json), loaded through the
// delegate's texture cache.
#pragma once

#include "delegate/scene_access.h"
#include "delegate/texture_cache.h"
#include "passes/frame_data.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace obscura::delegate {

struct BoundTexture {
    TexturePtr texture;
    VkSampler sampler = VK_NULL_HANDLE;
    passes::MaterialTexture params;  // sampled, scale and bias (with the renormalisation), channel, st transform
    std::string stPrimvar;           // the primvar the host was asked to serve as primvars:st
};

// nullopt when `input` ("diffuseColor", ...) has no texture file, or when the file cannot be
// read: then a warning naming the file goes to `warnings` and the input keeps its constant value.
std::optional<BoundTexture> readBoundTexture(SceneAccess& scene, TextureCache& cache, const std::string& input,
                                             std::vector<std::string>& warnings);

// The input's value over the whole texture: its average texel, channel-selected, scaled and
// biased as the UsdUVTexture output would be.
std::array<float, 3> averageColor(const BoundTexture& bound);

}  // namespace obscura::delegate
