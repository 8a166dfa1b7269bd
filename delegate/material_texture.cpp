#include "delegate/material_texture.h"

#include <algorithm>
#include <cmath>

namespace obscura::delegate {
namespace {

passes::TextureChannel parseChannel(const std::string& token) {
    if (token == "g") return passes::TextureChannel::G;
    if (token == "b") return passes::TextureChannel::B;
    if (token == "a") return passes::TextureChannel::A;
    if (token == "rgb") return passes::TextureChannel::Rgb;
    return passes::TextureChannel::R;
}

// Whether scale and bias read each texel channel c as +-(2 c - 1) and z as 2 z - 1: the texel is
// a unit normal's 0.5 n + 0.5 (up to mirrored x or y), which two-channel storage reproduces.
bool readsUnitNormals(const std::array<float, 4>& scale, const std::array<float, 4>& bias) {
    for (size_t c = 0; c < 2; ++c)
        if (std::abs(scale[c]) != 2.0f || bias[c] != -0.5f * scale[c]) return false;
    return scale[2] == 2.0f && bias[2] == -1.0f;
}

// One row of the texture coordinates' affine map (xyz; w stays unused). SceneAccess rejects
// non-finite values as bad prim data.
void readTransformRow(SceneAccess& scene, const std::string& name, std::array<float, 4>& row) {
    const std::array<float, 3> value = scene.getFloat3(name.c_str());
    std::copy(value.begin(), value.end(), row.begin());
}

}  // namespace

std::optional<BoundTexture> readBoundTexture(SceneAccess& scene, TextureCache& cache, const std::string& input,
                                             std::vector<std::string>& warnings) {
    const std::string prefix = "obscura:" + input + ":";
    auto attribute = [&](const char* field) { return prefix + field; };
    const std::string file = scene.getToken(attribute("file").c_str());
    if (file.empty()) return std::nullopt;
    const SourceColorSpace colorSpace = parseSourceColorSpace(scene.getToken(attribute("sourceColorSpace").c_str()));
    const std::array<float, 4> scale = scene.getFloat4(attribute("scale").c_str());
    const std::array<float, 4> bias = scene.getFloat4(attribute("bias").c_str());
    const auto channel = parseChannel(scene.getToken(attribute("channel").c_str()));
    // The cache decides whether the file can be stored as a normal map (not a float image).
    const TextureRole role = input == "normal" && channel == passes::TextureChannel::Rgb &&
                                     colorSpace == SourceColorSpace::Raw && readsUnitNormals(scale, bias)
                                 ? TextureRole::Normal
                                 : TextureRole::Material;
    auto loaded = cache.get(file, colorSpace, role);
    if (auto* problem = std::get_if<std::string>(&loaded)) {
        warnings.push_back("inputs:" + input + ": texture " + file + ": " + *problem + "; its constant value is used");
        return std::nullopt;
    }
    BoundTexture bound;
    bound.texture = std::get<TexturePtr>(loaded);
    for (const std::string& tile : bound.texture->leftOutTiles)
        warnings.push_back("inputs:" + input + ": UDIM tile " + tile + "; its square reads as missing");
    // A UDIM atlas is read within its squares (wrap modes do not apply) and without anisotropy.
    // XXX: lavapipe's anisotropic filter mixes in the lookups of a pixel's quad neighbours, which
    // differ across a tile seam (the clamp into each square), so the seam would bleed there.
    const bool udim = bound.texture->udimGrid[2] > 0.0f;
    bound.sampler = udim ? cache.sampler(WrapMode::Clamp, WrapMode::Clamp, false)
                         : cache.sampler(parseWrapMode(scene.getToken(attribute("wrapS").c_str())),
                                         parseWrapMode(scene.getToken(attribute("wrapT").c_str())));
    // A renormalised texture's map back to its values goes before the UsdUVTexture's own scale and
    // bias; both are affine per channel, so they fold into one (the talk's "two more constants per
    // texture" cost nothing more): (t * rs + rb) * s + b = t * (rs * s) + (rb * s + b).
    for (size_t c = 0; c < 4; ++c) {
        bound.params.scale[c] = bound.texture->renormScale[c] * scale[c];
        bound.params.bias[c] = bound.texture->renormBias[c] * scale[c] + bias[c];
    }
    bound.params.channel = uint32_t(channel);
    bound.params.encoding = uint32_t(bound.texture->twoChannelNormal ? passes::TexelEncoding::TwoChannelNormal
                                     : bound.texture->srgbEncoded    ? passes::TexelEncoding::Srgb
                                                                     : passes::TexelEncoding::Plain);
    bound.params.sampled = 1;
    bound.params.udimGrid = bound.texture->udimGrid;
    bound.stPrimvar = scene.getToken(attribute("st").c_str());
    readTransformRow(scene, attribute("transformS"), bound.params.transformS);
    readTransformRow(scene, attribute("transformT"), bound.params.transformT);
    const passes::MaterialTexture identity;
    bound.params.transformed = bound.params.transformS != identity.transformS || bound.params.transformT != identity.transformT;
    return bound;
}

std::array<float, 3> averageColor(const BoundTexture& bound) {
    const std::array<float, 4>& texel = bound.texture->average;
    const bool rgb = bound.params.channel == uint32_t(passes::TextureChannel::Rgb);
    std::array<float, 3> out{};
    for (size_t i = 0; i < 3; ++i)
        out[i] = (rgb ? texel[i] : texel[bound.params.channel]) * bound.params.scale[i] + bound.params.bias[i];
    return out;
}

}  // namespace obscura::delegate
