// The shadow atlas on the CPU (delegate/shadow_views.h): which views each light gets, where
// their tiles lie, which draws reach each view, and what happens when the atlas is full.
#include "delegate/shadow_views.h"

#include <gtest/gtest.h>

#include <numbers>
#include <set>

namespace obscura::delegate {
namespace {

passes::LightData distantLight(Vec3d direction) {
    passes::LightData light{};
    light.positionType = {0, 0, 0, float(passes::LightType::Distant)};
    light.directionAngle = {float(direction[0]), float(direction[1]), float(direction[2]), 0.0f};
    return light;
}

// A sphere (or, with `type`, a rect or disk) light at `position` pointing down -Y; `coneDegrees`
// as ShapingAPI's cone (180: unshaped).
passes::LightData localLight(Vec3d position, double coneDegrees = 180.0,
                             passes::LightType type = passes::LightType::Sphere) {
    passes::LightData light{};
    light.positionType = {float(position[0]), float(position[1]), float(position[2]), float(type)};
    light.directionAngle = {0, -1, 0, 0};
    light.radiance = {1, 1, 1, 0.1f};
    light.axisX = {0.5f, 0, 0, 0};
    light.axisY = {0, 0, 0.5f, 0};
    light.factors = {1, 1, 0, 0};
    float cone = float(coneDegrees * std::numbers::pi / 180.0);
    light.shaping = {cone, cone, 0, 0};
    return light;
}

ShadowedCamera cameraAt(Vec3d eye) {
    ShadowedCamera c;
    c.view = kIdentity;
    c.view[12] = -eye[0];
    c.view[13] = -eye[1];
    c.view[14] = -eye[2];
    // 90-degree perspective looking down -Z, near 0.1, far 1000 (Vulkan clip space).
    const double n = 0.1, f = 1000.0;
    c.projection = transpose(Matrix4d{1, 0, 0, 0, 0, -1, 0, 0, 0, 0, f / (n - f), n * f / (n - f), 0, 0, -1, 0});
    return c;
}

Aabb box(Vec3d lo, Vec3d hi) {
    Aabb b;
    b.extend(lo);
    b.extend(hi);
    return b;
}

struct Fixture {
    ShadowSettings settings;
    ShadowedCamera camera = cameraAt({0, 2, 10});
    // A ground slab and a small box on it.
    std::vector<Aabb> draws = {box({-20, -0.1, -20}, {20, 0, 20}), box({-1, 0, -1}, {1, 2, 1})};
    ShadowAtlasBuild build(std::vector<passes::LightData>& lights, std::vector<bool> casts = {}) {
        if (casts.empty()) casts.assign(lights.size(), true);
        return buildShadowAtlas({settings, camera, 0.1, 1000.0, draws}, lights, casts);
    }
};

TEST(ShadowViews, EachLightTypeGetsItsViews) {
    Fixture f;
    std::vector<passes::LightData> lights = {
        distantLight({0.3, -1, 0.2}), localLight({0, 5, 0}), localLight({2, 5, 0}, 40.0),
        localLight({0, 5, 2}, 180.0, passes::LightType::Rect), localLight({0, 5, 2}, 75.0, passes::LightType::Disk)};
    passes::LightData dome{};
    dome.positionType = {0, 0, 0, float(passes::LightType::Dome)};
    lights.push_back(dome);
    ShadowAtlasBuild b = f.build(lights);
    using P = passes::ShadowProjection;
    const std::array<std::pair<uint32_t, P>, 6> expected = {{{4, P::Cascades}, {6, P::Cube}, {1, P::Spot},
                                                            {6, P::Cube}, {6, P::Cube}, {0, P::Cascades}}};
    std::set<uint32_t> claimed;  // every view belongs to exactly one light
    for (size_t i = 0; i < lights.size(); ++i) {
        EXPECT_EQ(lights[i].shadow[1], expected[i].first) << "light " << i;
        if (expected[i].first == 0) continue;
        EXPECT_EQ(lights[i].shadow[2], uint32_t(expected[i].second)) << "light " << i;
        for (uint32_t v = lights[i].shadow[0]; v < lights[i].shadow[0] + lights[i].shadow[1]; ++v)
            EXPECT_TRUE(claimed.insert(v).second) << "view " << v;
    }
    EXPECT_EQ(claimed.size(), 23u);
    EXPECT_EQ(*claimed.rbegin(), 22u);
    EXPECT_EQ(b.atlas.views.size(), 23u);
    EXPECT_EQ(b.records.size(), 23u);
    EXPECT_EQ(b.lightsLeftUnshadowed, 0u);
    // The distant light claims first; its cascades end in increasing view distances, perspective
    // views leave that field 0.
    EXPECT_EQ(lights[0].shadow[0], 0u);
    for (uint32_t c = 1; c < 4; ++c) EXPECT_LT(b.records[c - 1].params[1], b.records[c].params[1]);
    EXPECT_EQ(b.records[4].params[1], 0.0f);
}

TEST(ShadowViews, CascadesStartAtTheNearestSceneThePictureHolds) {
    // The eye 2 above the ground looks along it with a 90-degree view: the ground enters the
    // picture 2 ahead. The cascades start a quarter-octave step from the near plane at most 10%
    // plus a step before that, 0.1 x 2^(16/4) = 1.6, and the first one ends where the practical
    // split of [1.6, end] puts it.
    Fixture f;
    std::vector<passes::LightData> lights = {distantLight({0.3, -1, 0.2})};
    ShadowAtlasBuild b = f.build(lights);
    ASSERT_EQ(b.records.size(), 4u);
    const double end = b.records[3].params[1];
    EXPECT_NEAR(b.records[0].params[1], cascadeSplits(1.6, end, 4, 0.75)[1], 1e-4 * end);
    // A draw around the eye: the cascades start at the near plane again.
    f.draws.push_back(box({-1, 1, 9}, {1, 3, 11}));
    std::vector<passes::LightData> again = {distantLight({0.3, -1, 0.2})};
    ShadowAtlasBuild near = f.build(again);
    EXPECT_NEAR(near.records[0].params[1], cascadeSplits(0.1, end, 4, 0.75)[1], 1e-4 * end);
    EXPECT_LT(near.records[0].params[1], b.records[0].params[1]);
}

TEST(ShadowViews, TilesPackWithoutOverlapInsideTheAtlas) {
    Fixture f;
    f.settings.resolution = 512;
    std::vector<passes::LightData> lights = {distantLight({0, -1, 0}), localLight({0, 5, 0}), localLight({3, 5, 0})};
    ShadowAtlasBuild b = f.build(lights);
    ASSERT_EQ(b.atlas.views.size(), 16u);
    std::set<std::pair<uint32_t, uint32_t>> corners;
    for (size_t v = 0; v < b.atlas.views.size(); ++v) {
        const auto& view = b.atlas.views[v];
        EXPECT_EQ(view.size, 512u);
        EXPECT_LE(view.x + view.size, b.atlas.width);
        EXPECT_LE(view.y + view.size, b.atlas.height);
        EXPECT_TRUE(corners.insert({view.x, view.y}).second) << "two views share a tile";
        EXPECT_EQ(b.records[v].tileRect[0], float(view.x));
        EXPECT_EQ(b.records[v].tileRect[3], float(view.y + view.size - 1));
    }
    EXPECT_EQ(b.atlas.width, 4u * 512u);
    EXPECT_EQ(b.atlas.height, 4u * 512u);
}

TEST(ShadowViews, DrawsOutsideAViewAreNotRenderedIntoIt) {
    Fixture f;
    // A box far off to the side of a spot pointing straight down at the origin.
    f.draws.push_back(box({500, 0, 500}, {501, 1, 501}));
    std::vector<passes::LightData> lights = {localLight({0, 5, 0}, 30.0)};
    ShadowAtlasBuild b = f.build(lights);
    ASSERT_EQ(b.atlas.views.size(), 1u);
    EXPECT_EQ(b.atlas.views[0].draws, (std::vector<uint32_t>{0, 1}));
}

TEST(ShadowViews, LightsWithoutShadowsGetNoViews) {
    Fixture f;
    std::vector<passes::LightData> lights = {distantLight({0, -1, 0}), localLight({0, 5, 0})};
    ShadowAtlasBuild b = f.build(lights, {false, true});
    EXPECT_EQ(lights[0].shadow[1], 0u) << "inputs:shadow:enable false";
    EXPECT_EQ(lights[1].shadow[1], 6u);
    f.settings.enabled = false;
    b = f.build(lights);
    EXPECT_TRUE(b.atlas.views.empty()) << "render setting shadows off";
    EXPECT_EQ(b.atlas.width, 1u);
    EXPECT_EQ(lights[1].shadow[1], 0u);
}

TEST(ShadowViews, AFullAtlasLeavesLaterLightsUnshadowed) {
    Fixture f;
    f.settings.resolution = 4096;  // 2 x 2 tiles fit in the atlas
    std::vector<passes::LightData> lights = {distantLight({0, -1, 0}), localLight({0, 5, 0}), localLight({2, 5, 0}, 30.0)};
    f.settings.cascades = 3;
    ShadowAtlasBuild b = f.build(lights);
    EXPECT_EQ(lights[0].shadow[1], 3u);
    EXPECT_EQ(lights[1].shadow[1], 0u) << "six faces do not fit beside three cascades";
    EXPECT_EQ(lights[2].shadow[1], 1u) << "a later light that fits still gets its map";
    EXPECT_EQ(b.lightsLeftUnshadowed, 1u);
}

TEST(ShadowViews, LightsNearerTheCameraClaimTilesFirst) {
    Fixture f;
    f.settings.resolution = 2048;  // 4 x 4 tiles: two cubes fit, three do not
    std::vector<passes::LightData> lights = {localLight({0, 5, -300}), localLight({0, 5, 0}), localLight({1, 5, 5})};
    lights[0].factors[3] = 10.0f;  // influence ranges: the far light's sphere stays far from the camera
    lights[1].factors[3] = 10.0f;
    lights[2].factors[3] = 10.0f;
    ShadowAtlasBuild b = f.build(lights);
    EXPECT_EQ(lights[0].shadow[1], 0u) << "the farthest light loses its shadow";
    EXPECT_EQ(lights[1].shadow[1], 6u);
    EXPECT_EQ(lights[2].shadow[1], 6u);
    EXPECT_EQ(lights[2].shadow[0], 0u) << "the nearest light's views come first";
    EXPECT_EQ(b.lightsLeftUnshadowed, 1u);
}

}  // namespace
}  // namespace obscura::delegate
