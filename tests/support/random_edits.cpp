#include "tests/support/random_edits.h"

#include <array>
#include <cmath>

namespace obscura::test {
namespace {

constexpr int kCardSlots = 8;
std::string cardPath(int i) { return "/Cards/card" + std::to_string(i); }
std::string cardMaterial(int i) { return "/Looks/card" + std::to_string(i); }

std::vector<std::array<float, 3>> cardPoints(float bend) {
    return {{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, bend}, {0.5f, 0.5f, 0.0f}, {-0.5f, 0.5f, -bend}};
}

}  // namespace

RandomEditScene::RandomEditScene(InMemoryHost& host, uint32_t seed, int width, int height)
    : host_(host), random_(seed), baseWidth_(width), baseHeight_(height), width_(width), height_(height) {
    host_.addCamera("/Camera", translation(0, 0, 6));
    host_.addPrim("distantLight", "/Sun", {{"inputs:intensity", HostValue::floatValue(2.0f)}});
    host_.addPrim("sphereLight", "/Lamp",
                  {{"inputs:intensity", HostValue::floatValue(5.0f)}, {"inputs:radius", HostValue::floatValue(0.2f)}},
                  translation(1, 1, 2));
    host_.addRenderBuffer("/Buffers/color", "float32Vec4", width_, height_);
    host_.addRenderBuffer("/Buffers/id", "int32", width_, height_);
    for (int i = 0; i < kCardSlots / 2; ++i) addCard(i);
}

void RandomEditScene::addCard(int i) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    host_.addPrim("material", cardMaterial(i),
                  {{"inputs:diffuseColor", HostValue::float3(unit(random_), unit(random_), unit(random_))},
                   {"inputs:roughness", HostValue::floatValue(0.3f + 0.7f * unit(random_))}});
    host_.addPrim("mesh", cardPath(i),
                  {{"points", HostValue::points(cardPoints(0.0f))},
                   {"faceVertexCounts", HostValue::intArray({4})},
                   {"faceVertexIndices", HostValue::intArray({0, 1, 2, 3})},
                   {"material:binding", HostValue::path(cardMaterial(i))}},
                  translation(-2.0 + 0.6 * i, 0.3 * (i % 3) - 0.3, -0.1 * i));
    cards_.insert(i);
}

void RandomEditScene::editOnce() {
    const ObscuraApiV1& api = host_.api();
    ObscuraDelegate d = host_.delegate();
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_int_distribution<int> slot(0, kCardSlots - 1);
    int card = slot(random_);
    bool present = cards_.count(card) > 0;
    switch (std::uniform_int_distribution<int>(0, 7)(random_)) {
        case 0:  // transform
            if (!present) break;
            host_.setTransform(cardPath(card), translation(4.0 * unit(random_) - 2.0, 2.0 * unit(random_) - 1.0, -unit(random_)));
            api.markDirty(d, cardPath(card).c_str(), OBSCURA_DIRTY_TRANSFORM);
            break;
        case 1:  // points
            if (!present) break;
            host_.set(cardPath(card), "points", HostValue::points(cardPoints(0.4f * unit(random_) - 0.2f)));
            api.markDirty(d, cardPath(card).c_str(), OBSCURA_DIRTY_POINTS);
            break;
        case 2:  // material
            if (!present) break;
            host_.set(cardMaterial(card), "inputs:diffuseColor", HostValue::float3(unit(random_), unit(random_), unit(random_)));
            api.markDirty(d, cardMaterial(card).c_str(), OBSCURA_DIRTY_PARAMS);
            break;
        case 3:  // light
            host_.set("/Lamp", "inputs:intensity", HostValue::floatValue(10.0f * unit(random_)));
            host_.setTransform("/Lamp", translation(2.0 * unit(random_) - 1.0, 2.0 * unit(random_) - 1.0, 1.0 + unit(random_)));
            api.markDirty(d, "/Lamp", OBSCURA_DIRTY_PARAMS | OBSCURA_DIRTY_TRANSFORM);
            break;
        case 4:  // add or remove a card
            if (present) {
                api.removePrim(d, cardPath(card).c_str());
                api.removePrim(d, cardMaterial(card).c_str());
                cards_.erase(card);
            } else {
                addCard(card);
            }
            break;
        case 5: {  // resize
            static constexpr std::array<std::array<int, 2>, 3> kScales = {{{4, 4}, {3, 4}, {4, 3}}};
            const auto& s = kScales[std::uniform_int_distribution<size_t>(0, kScales.size() - 1)(random_)];
            width_ = baseWidth_ * s[0] / 4;
            height_ = baseHeight_ * s[1] / 4;
            for (const char* buffer : {"/Buffers/color", "/Buffers/id"}) {
                host_.set(buffer, "dimensions", HostValue::int2(width_, height_));
                api.markDirty(d, buffer, OBSCURA_DIRTY_PARAMS);
            }
            break;
        }
        case 6: {  // exposure
            ObscuraValue v{OBSCURA_VALUE_FLOAT, 0, 1, nullptr};
            float exposure = 2.0f * unit(random_) - 1.0f;
            v.data = &exposure;
            api.setRenderSetting(d, "exposure", &v);
            break;
        }
        default: {  // an effect on or off
            static const char* const kToggles[] = {"ssao", "taa", "shadows"};
            const char* key = kToggles[std::uniform_int_distribution<int>(0, 2)(random_)];
            int32_t on = unit(random_) < 0.5f ? 1 : 0;
            ObscuraValue v{OBSCURA_VALUE_BOOL, 0, 1, &on};
            api.setRenderSetting(d, key, &v);
            break;
        }
    }
}

ObscuraStatus RandomEditScene::editAndRender() {
    int edits = std::uniform_int_distribution<int>(1, 3)(random_);
    for (int i = 0; i < edits; ++i) editOnce();
    return host_.render("/Camera", {{"color", "/Buffers/color"}, {"primId", "/Buffers/id"}});
}

}  // namespace obscura::test
