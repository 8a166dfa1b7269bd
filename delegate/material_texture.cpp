#include "delegate/material_texture.h"

namespace obscura::delegate {
namespace {

passes::TextureChannel parseChannel(const std::string& token) {
    if (token == "g") return passes::TextureChannel::G;
    if (token == "b") return passes::TextureChannel::B;
    if (token == "a") return passes::TextureChannel::A;
    if (token == "rgb") return passes::TextureChannel::Rgb;
    return passes::TextureChannel::R;
}

}  // namespace

std::optional<BoundTexture> readBoundTexture(SceneAccess& scene, TextureCache& cache, const std::string& input,
                                             std::vector<std::string>& warnings) {
    const std::string prefix = "obscura:" + input + ":";
    auto attribute = [&](const char* field) { return prefix + field; };
    const std::string file = scene.getToken(attribute("file").c_str());
    if (file.empty()) return std::nullopt;
    auto loaded = cache.get(file, parseSourceColorSpace(scene.getToken(attribute("sourceColorSpace").c_str())));
    if (auto* problem = std::get_if<std::string>(&loaded)) {
        warnings.push_back("inputs:" + input + ": texture " + file + ": " + *problem + "; its constant value is used");
        return std::nullopt;
    }
    BoundTexture bound;
    bound.texture = std::get<TexturePtr>(loaded);
    bound.sampler = cache.sampler(parseWrapMode(scene.getToken(attribute("wrapS").c_str())),
                                  parseWrapMode(scene.getToken(attribute("wrapT").c_str())));
    bound.params.scale = scene.getFloat4(attribute("scale").c_str());
    bound.params.bias = scene.getFloat4(attribute("bias").c_str());
    bound.params.channel = uint32_t(parseChannel(scene.getToken(attribute("channel").c_str())));
    bound.params.sampled = 1;
    bound.stPrimvar = scene.getToken(attribute("st").c_str());
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
