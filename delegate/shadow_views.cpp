#include "delegate/shadow_views.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::delegate {
namespace {

// Weight of the logarithmic split against the uniform one (Zhang et al. 2006 suggest a blend;
// 0.75 keeps the first cascade a useful size with a near plane close to the camera).
constexpr double kCascadeSplitLambda = 0.75;

// The narrowest blocker search of the lookup (shadow_sampling.glsl), 1.5 texels around the sample
// with a 2x2 gather at each tap, reads up to 2.5 texels from it;
// cube faces and spot maps extend their field of view by 3 texels so no such lookup inside the
// face (or the cone) needs texels beyond the map. Wider penumbra filters are clamped to the tile.
constexpr uint32_t kGuardTexels = 3;

// A ShapingAPI cone up to this half-angle gets one perspective map; wider cones get a cube. At
// 60 degrees the map's texels on the axis are tan(60°) = 1.7 times a cube face's; wider, one
// map spreads too thin (and reaches 180 degrees at a 90-degree cone).
constexpr double kSpotMapMaxCone = std::numbers::pi / 3.0;

// Row-vector matrix from a view's clip space to atlas texels within its tile: the viewport
// transform of the tile (x0 + (ndc + 1) size / 2), kept homogeneous so that the lookup divides
// by w once.
Matrix4d clipToAtlas(uint32_t x0, uint32_t y0, uint32_t size) {
    Matrix4d m = kIdentity;
    double half = 0.5 * double(size);
    m[0] = half;
    m[5] = half;
    m[12] = double(x0) + half;
    m[13] = double(y0) + half;
    return m;
}

struct PendingView {
    Matrix4d viewProjection;
    double texelWorldSize;
    double cascadeEnd;  // cascades only, else 0
    // ShadowViewData::params.zw: cascades the depth span along the light and 0, perspective views
    // their near and far planes.
    std::array<double, 2> depthRange;
};

// Where the camera's cascades end: the farthest scene point ahead of the camera, rounded up to
// a quarter-octave step from the near plane. A continuous fit would change every cascade's size
// whenever the camera moves; the steps keep them constant except at rare jumps (stability).
double cascadeRangeEnd(const ShadowedCamera& camera, double near, double far, const Aabb& scene) {
    double deepest = 0.0;
    for (const Vec3d& corner : scene.corners()) deepest = std::max(deepest, -transformPoint(corner, camera.view)[2]);
    if (deepest <= near) return near;  // nothing in front of the camera
    double steps = std::ceil(4.0 * std::log2(deepest / near));
    return std::min(far, near * std::exp2(steps / 4.0));
}

// Where the camera's cascades start: the nearest point of the scene the view holds (the depth
// range of sample distribution shadow maps, Lauritzen et al. 2011, bounded by the draws' boxes
// where they read it from the depth buffer), with 10% to spare and rounded down to a quarter-octave
// step from the near plane, as the end is. Cascades that start at the near plane spend their finest
// slices where nothing lies: a camera two metres above a floor sees none of it within a few metres.
double cascadeRangeStart(const ShadowedCamera& camera, double near, double end, const std::vector<Aabb>& drawBounds) {
    const double nearest = nearestDistanceInView(drawBounds, camera);
    if (!(0.9 * nearest > near)) return near;
    const double start = near * std::exp2(std::floor(4.0 * std::log2(0.9 * nearest / near)) / 4.0);
    return start < end ? start : near;
}

// The order in which shadow-casting lights claim atlas tiles, for when not all fit: distant
// lights first (they light everything), then local lights by how close their influence sphere
// comes to the camera.
std::vector<size_t> shadowPriority(const std::vector<passes::LightData>& lights, const std::vector<bool>& castsShadows,
                                   const ShadowedCamera& camera) {
    Matrix4d viewToWorld = kIdentity;
    invert(camera.view, viewToWorld);
    Vec3d eye = transformPoint({0, 0, 0}, viewToWorld);
    auto gap = [&](const passes::LightData& light) {
        if (passes::LightType(uint32_t(light.positionType[3])) == passes::LightType::Distant) return -1e30;
        Vec3d d = {light.positionType[0] - eye[0], light.positionType[1] - eye[1], light.positionType[2] - eye[2]};
        return length(d) - double(light.factors[3]);
    };
    std::vector<size_t> order;
    for (size_t i = 0; i < lights.size(); ++i)
        if (castsShadows[i]) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return gap(lights[a]) < gap(lights[b]); });
    return order;
}

}  // namespace

ShadowAtlasBuild buildShadowAtlas(const ShadowInputs& in, std::vector<passes::LightData>& lights,
                                  const std::vector<bool>& castsShadows) {
    ShadowAtlasBuild build;
    for (auto& light : lights) light.shadow = {0, 0, 0, 0};
    Aabb scene;
    for (const Aabb& box : in.drawBounds) scene.merge(box);
    if (!in.settings.enabled || scene.empty()) return build;

    const uint32_t resolution = in.settings.resolution;
    const uint32_t tilesPerSide = std::max(1u, kMaxShadowAtlasSide / resolution);
    const uint32_t maxViews = tilesPerSide * tilesPerSide;
    const double cascadeEnd = cascadeRangeEnd(in.camera, in.cameraNear, in.cameraFar, scene);
    std::vector<double> splits;
    if (cascadeEnd > in.cameraNear)
        splits = cascadeSplits(cascadeRangeStart(in.camera, in.cameraNear, cascadeEnd, in.drawBounds), cascadeEnd,
                               in.settings.cascades, kCascadeSplitLambda);

    std::vector<PendingView> views;
    for (size_t i : shadowPriority(lights, castsShadows, in.camera)) {
        passes::LightData& light = lights[i];
        auto type = passes::LightType(uint32_t(light.positionType[3]));
        std::vector<PendingView> lightViews;
        passes::ShadowProjection projection = passes::ShadowProjection::Cascades;
        if (type == passes::LightType::Distant && !splits.empty()) {
            Vec3d direction = {light.directionAngle[0], light.directionAngle[1], light.directionAngle[2]};
            for (size_t c = 0; c + 1 < splits.size(); ++c) {
                Cascade cascade = fitStableCascade(in.camera, splits[c], splits[c + 1], direction, scene, resolution);
                lightViews.push_back({cascade.viewProjection, cascade.texelWorldSize, splits[c + 1], {cascade.depthSpan, 0.0}});
            }
        } else if (type == passes::LightType::Sphere || type == passes::LightType::Rect ||
                   type == passes::LightType::Disk || type == passes::LightType::Cylinder) {
            Vec3d position = {light.positionType[0], light.positionType[1], light.positionType[2]};
            double far = 0.0;
            for (const Vec3d& corner : scene.corners()) {
                Vec3d d = {corner[0] - position[0], corner[1] - position[1], corner[2] - position[2]};
                far = std::max(far, length(d));
            }
            // Nothing beyond the light's influence range receives its light.
            if (light.factors[3] > 0.0f) far = std::min(far, double(light.factors[3]));
            if (far <= 0.0) continue;
            // Depth precision of a perspective map falls with near/far; the emitter's size is a
            // natural near plane (occluders closer to the light's centre than that are beside or
            // inside the emitter, and cast no sensible point-light shadow).
            double emitterSize = type == passes::LightType::Sphere || type == passes::LightType::Cylinder
                                     ? double(light.radiance[3])
                                     : std::min(std::hypot(light.axisX[0], light.axisX[1], light.axisX[2]),
                                                std::hypot(light.axisY[0], light.axisY[1], light.axisY[2]));
            double near = std::clamp(emitterSize, 1e-3 * far, 0.5 * far);
            double cone = light.shaping[0];
            if (cone <= kSpotMapMaxCone) {
                Vec3d axis = {light.directionAngle[0], light.directionAngle[1], light.directionAngle[2]};
                ShadowProjection spot = spotProjection(position, axis, cone, near, far, resolution, kGuardTexels);
                lightViews.push_back({spot.viewProjection, spot.texelWorldSize, 0.0, {near, far}});
                projection = passes::ShadowProjection::Spot;
            } else {
                for (const ShadowProjection& face : cubeFaceProjections(position, near, far, resolution, kGuardTexels))
                    lightViews.push_back({face.viewProjection, face.texelWorldSize, 0.0, {near, far}});
                projection = passes::ShadowProjection::Cube;
            }
        }
        if (lightViews.empty()) continue;
        if (views.size() + lightViews.size() > maxViews) {
            ++build.lightsLeftUnshadowed;
            continue;
        }
        light.shadow = {uint32_t(views.size()), uint32_t(lightViews.size()), uint32_t(projection), 0};
        views.insert(views.end(), lightViews.begin(), lightViews.end());
    }
    if (views.empty()) return build;

    // Tiles in rows, as square an atlas as the count allows.
    const uint32_t count = uint32_t(views.size());
    const uint32_t columns = uint32_t(std::ceil(std::sqrt(double(count))));
    const uint32_t rows = (count + columns - 1) / columns;
    build.atlas.width = columns * resolution;
    build.atlas.height = rows * resolution;
    for (uint32_t v = 0; v < count; ++v) {
        const PendingView& pending = views[v];
        passes::ShadowMapView view;
        view.viewProjection = toFloats<passes::Mat4>(pending.viewProjection);
        view.x = (v % columns) * resolution;
        view.y = (v / columns) * resolution;
        view.size = resolution;
        for (uint32_t d = 0; d < in.drawBounds.size(); ++d)
            if (!outsideClipVolume(in.drawBounds[d], pending.viewProjection)) view.draws.push_back(d);
        passes::ShadowViewData record{};
        record.worldToAtlas = toFloats<passes::Mat4>(multiply(pending.viewProjection, clipToAtlas(view.x, view.y, view.size)));
        record.tileRect = {float(view.x), float(view.y), float(view.x + view.size - 1), float(view.y + view.size - 1)};
        record.params = {float(pending.texelWorldSize), float(pending.cascadeEnd), float(pending.depthRange[0]),
                         float(pending.depthRange[1])};
        build.records.push_back(record);
        build.viewProjections.push_back(pending.viewProjection);
        build.atlas.views.push_back(std::move(view));
    }
    return build;
}

}  // namespace obscura::delegate
