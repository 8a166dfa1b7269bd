// The kinds of light and the material features the lighting pass and the G-buffer are built for
// (specialization constants, passes/frame_data.h): each bit follows from the record it names.
#include "passes/frame_data.h"

#include <gtest/gtest.h>

#include <numbers>

namespace obscura::passes {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

TEST(SpecializationKinds, LightKindsNameTypeShadowProjectionShapingAndTexturedDome) {
    LightData sun{};
    sun.positionType[3] = float(LightType::Distant);
    sun.shadow = {0, 4, uint32_t(ShadowProjection::Cascades), 0};
    EXPECT_EQ(lightKind(sun), (1u << 0) | (1u << 8));

    LightData spot{};
    spot.positionType[3] = float(LightType::Sphere);
    spot.shaping = {0.5f, 0.4f, 0.0f, 0.0f};
    spot.shadow = {4, 1, uint32_t(ShadowProjection::Spot), 0};
    EXPECT_EQ(lightKind(spot), (1u << 1) | (1u << 10) | kLightKindShaped);

    LightData bulb = spot;
    bulb.shaping = {kPi, kPi, 0.0f, 0.0f};  // unshaped: all around
    bulb.shadow = {};
    EXPECT_EQ(lightKind(bulb), 1u << 1);
    bulb.shaping[2] = 2.0f;  // a focus alone shapes it
    EXPECT_EQ(lightKind(bulb), (1u << 1) | kLightKindShaped);

    LightData dome{};
    dome.positionType[3] = float(LightType::Dome);
    EXPECT_EQ(lightKind(dome), 1u << 2);
    dome.factors[2] = 1.0f;
    EXPECT_EQ(lightKind(dome), (1u << 2) | kLightKindTexturedDome);
}

TEST(SpecializationKinds, MaterialFeaturesNameWhatTheMaterialSamples) {
    MaterialData plain{};
    EXPECT_EQ(materialFeatures(plain), 0u);
    MaterialData anisotropic = plain;
    anisotropic.anisotropy[0] = 0.5f;
    EXPECT_EQ(materialFeatures(anisotropic), uint32_t(kMaterialAnisotropic));

    MaterialData textured = plain;
    textured.textures[kTextureRoughness].sampled = 1;
    EXPECT_EQ(materialFeatures(textured), uint32_t(kMaterialTextured));
    textured.textures[kTextureNormal].sampled = 1;
    textured.textures[kTextureNormal].transformed = 1;
    textured.textures[kTextureDiffuse].udimGrid = {1.0f, 0.0f, 0.0f, 1.0f};  // not sampled: no UDIM
    EXPECT_EQ(materialFeatures(textured),
              kMaterialTextured | kMaterialNormalMap | kMaterialTransformedTexture);
    textured.textures[kTextureDiffuse].sampled = 1;
    textured.textures[kTextureDiffuse].udimGrid = {1.0f, 0.0f, 2.0f, 1.0f};
    EXPECT_EQ(materialFeatures(textured), kMaterialTextured | kMaterialNormalMap |
                                                      kMaterialTransformedTexture | kMaterialUdim);
}

}  // namespace
}  // namespace obscura::passes
