// Shadow lookups, per pixel (seed 000 "Deferred MSAA \ performance shortcuts": sun shadows are
// computed at pixel frequency): choose a light's view in the shadow atlas (a cascade by view
// distance, a cube face by the major axis, a spot's one map), offset the receiver's depth along its
// normal, and filter: a penumbra as wide as the light's size makes it (percentage-closer soft
// shadows), at least one texel's bilinear ramp.
//
// The includer declares, before including this file:
//   ShadowViewData shadowViews[]   the frame's views (a storage buffer, frame_data.glsl)
//   sampler2D shadowAtlas          the atlas (passes/shadow_maps.h) with a nearest-filtering sampler
#ifndef OBSCURA_SHADOW_SAMPLING_GLSL
#define OBSCURA_SHADOW_SAMPLING_GLSL

#include "device_traits.glsl"
#include "interleaved_gradient_noise.glsl"
#include "light_evaluation.glsl"

// Normal offset (Holbein 2011, "Normal offset shadows"): the receiver's depth is taken this many
// texels of its view along its normal, which keeps it off the surface's own depths at grazing
// angles to the light; the rasteriser's slope-scaled bias (passes/shadow_maps.cpp) covers the
// filter's footprint. Only the depth: the lookup stays at the receiver, as moving it across the
// map by the offset (sin of the normal's angle to the light x 1.5 texels) moved the shadow's edges
// by as much, wider than the physical penumbra of a small light on a coarse cascade.
const float SHADOW_NORMAL_OFFSET_TEXELS = 1.5;

// The narrowest blocker search, in texels: it reaches the 2x2 texels of a bilinear lookup.
const float SHADOW_MIN_SEARCH_RADIUS_TEXELS = 1.5;
// The widest penumbra filter, in texels of the view, and the farthest the blocker search looks.
// Wider penumbrae (a large light far above its receiver, or a fine cascade) are cut to this
// radius: their edges come out sharper than the light makes them.
const float SHADOW_MAX_FILTER_RADIUS_TEXELS = 32.0;
// The taps of the blocker search and of the penumbra filter, each a gather of 2x2 texels, are
// the SHADOW_DISC_TAPS of one spiral (vogelRadius, nextVogelDirection).
// A receiver's depth slope is trusted up to this tangent of its angle to the light's view (84°).
const float SHADOW_MAX_RECEIVER_SLOPE = 10.0;

// --- Percentage-closer soft shadows ---------------------------------------------------------
// Fernando 2005, "Percentage-closer soft shadows": search the map for blockers over the region
// the light subtends from the receiver, take their average depth, and filter over the penumbra a
// planar blocker at that depth would cast: w = (d_receiver - d_blocker) tan(theta) for a distant
// light of angular diameter theta, w = size (d_receiver - d_blocker) / d_blocker for a local
// light of diameter `size` (similar triangles). Both regions are discs sampled by a Vogel
// spiral (Vogel 1979; Jimenez 2014 uses it for shadows) turned per pixel by interleaved gradient
// noise and per frame by the golden ratio, so a still's temporal mean (taa:frames jittered frames)
// integrates the disc far more finely than one frame's taps. Each tap gathers 2x2 texels compared
// against the receiver's plane (receiver-plane depth bias, Isidoro 2006), so wide footprints do not
// shadow a receiver tilted to the light with its own depths.

// What the filters know of the receiver in one view.
struct ShadowReceiver {
    vec3 atlas;       // atlas texel coordinates and depth of the (normal-offset) receiver
    vec2 depthSlope;  // the receiver plane's depth change per texel along x and y
    vec4 tileRect;    // the view's tile: first and last texel
};

// The receiver at world position `position` with unit normal `normal`, seen through `view`, its
// depth normal-offset; `texelWorld` is a texel's world size there (the tangents' length).
ShadowReceiver shadowReceiver(uint view, vec3 position, vec3 normal, float texelWorld) {
    mat4 toAtlas = shadowViews[view].worldToAtlas;
    vec4 clip = toAtlas * vec4(position, 1.0);
    vec3 atlas = clip.xyz / clip.w;
    vec4 offset = toAtlas * vec4(position + normal * (texelWorld * SHADOW_NORMAL_OFFSET_TEXELS), 1.0);
    ShadowReceiver r;
    r.atlas = vec3(atlas.xy, offset.z / offset.w);
    r.tileRect = shadowViews[view].tileRect;
    // Two tangents of the receiver's plane, projected: dz = slope . dxy for both gives the slope.
    // Depth over the map is affine on a plane for orthographic and perspective views alike.
    vec3 helper = abs(normal.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 t1 = normalize(cross(helper, normal)) * texelWorld;
    vec3 t2 = cross(normal, t1);
    vec4 c1 = toAtlas * vec4(position + t1, 1.0);
    vec4 c2 = toAtlas * vec4(position + t2, 1.0);
    vec3 d1 = c1.xyz / c1.w - atlas, d2 = c2.xyz / c2.w - atlas;
    mat2 tangentsInMap = mat2(d1.xy, d2.xy);
    float det = determinant(tangentsInMap);
    // Edge-on to the view (det ~ 0) the plane says nothing: no slope, a plain depth comparison.
    r.depthSlope = abs(det) > 1e-8 ? inverse(transpose(tangentsInMap)) * vec2(d1.z, d2.z) : vec2(0.0);
    // Limit the slope where the plane turns edge-on to the view: a plane tilted by a from facing
    // the view changes depth by about tan(a) times what one texel of it along the view's depth
    // axis adds, and the tangents measure sin(a) of that.
    float depthPerTexel = length(d1.xy) > 0.0 ? max(abs(d1.z), abs(d2.z)) / max(length(d1.xy), length(d2.xy)) : 0.0;
    float limit = SHADOW_MAX_RECEIVER_SLOPE * max(depthPerTexel, 1e-7);
    float slope = length(r.depthSlope);
    if (slope > limit) r.depthSlope *= limit / slope;
    return r;
}

// The taps of a Vogel spiral over the unit disc (equal areas per tap): tap i at radius
// sqrt((i + 1/2) / n), its direction the last tap's turned by the golden angle (a constant
// rotation), the first's the pixel's turn. One sine and cosine per light where turning each tap's
// angle cost two a tap: on a CPU device 64 of its longest instructions per light and pixel (and a
// table of the taps cost it more: it fetches a uniform array element per lane).
const float GOLDEN_ANGLE = 2.39996323;
const int SHADOW_DISC_TAPS = 16;

float vogelRadius(int i) { return sqrt((float(i) + 0.5) / float(SHADOW_DISC_TAPS)); }

// A tap's direction turned on to the next tap's.
vec2 nextVogelDirection(vec2 direction) {
    const float c = cos(GOLDEN_ANGLE), s = sin(GOLDEN_ANGLE);
    return vec2(direction.x * c - direction.y * s, direction.x * s + direction.y * c);
}

// The 2x2 texels around atlas position q (kept inside the tile): their depths (gather order x, y,
// z, w), where the receiver's plane lies at each of their centres, and q's place between their
// centres (the bilinear fractions).
void gatherAgainstPlane(ShadowReceiver r, vec2 q, out vec4 depths, out vec4 plane, out vec2 fraction) {
    q = clamp(q, r.tileRect.xy + 0.5, r.tileRect.zw + 0.49) - 0.5;  // texel centres at whole numbers
    vec2 base = floor(q);  // the lower texel of the pair in each axis
    fraction = q - base;
    depths = textureGather(shadowAtlas, (base + 1.0) / vec2(textureSize(shadowAtlas, 0)));
    vec4 dx = base.x + 0.5 - r.atlas.x + vec4(0.0, 1.0, 1.0, 0.0);
    vec4 dy = base.y + 0.5 - r.atlas.y + vec4(1.0, 1.0, 0.0, 0.0);
    plane = r.atlas.z + r.depthSlope.x * dx + r.depthSlope.y * dy;
}

// Percentage-closer filtering (Reeves et al. 1987) at its smallest footprint: the light's share
// through the 2x2 texels around atlas position q, each compared with the receiver's plane,
// weighted bilinearly, so the result moves smoothly with q. A hard shadow's edge is one texel's
// ramp; lavapipe offers no linear filtering of depth formats, hence the gather.
float bilinearVisibility(ShadowReceiver r, vec2 q) {
    vec4 depths, plane;
    vec2 f;
    gatherAgainstPlane(r, q, depths, plane, f);
    vec4 weights = vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
    return dot(step(plane, depths), weights);
}

// Visible share of the disc of `radius` texels around the receiver, a bilinear lookup per tap.
float discFilter(ShadowReceiver r, float radius, vec2 firstDirection) {
    float lit = 0.0;
    vec2 direction = firstDirection;
    for (int i = 0; i < SHADOW_DISC_TAPS; ++i, direction = nextVogelDirection(direction))
        lit += bilinearVisibility(r, r.atlas.xy + radius * vogelRadius(i) * direction);
    return lit / float(SHADOW_DISC_TAPS);
}

// How a view's stored depth maps to distance: orthographic (cascades) depth 0..1 spans
// params.z world units along the light; perspective maps store z/w between params.z (near) and
// params.w (far), so distance along the axis = near far / (far - depth (far - near)).
// `p`: the view's params; four depths at once (a gather's texels).
vec4 viewDistancesOfDepths(vec4 p, bool perspective, vec4 depths) {
    return perspective ? p.z * p.w / (p.w - depths * (p.w - p.z)) : depths * p.z;
}

// Percentage-closer soft shadows for a light of `lightSize` (the tangent of a distant light's half
// angle, or a local light's radius, world units): the penumbra filter's radius in texels, or -1
// where the blocker search finds nothing (fully lit). `texelWorld`: a texel's world size at the
// receiver.
float softShadowRadius(uint view, bool perspective, ShadowReceiver r, float lightSize, float texelWorld,
                       vec2 firstDirection) {
    vec4 params = shadowViews[view].params;
    float receiverDistance = viewDistancesOfDepths(params, perspective, vec4(r.atlas.z)).x;
    // The region of the map where blockers can hide part of the light: from the receiver the light
    // spans a cone; its section is widest at the map's near end (depth 0, or the near plane).
    float nearest = perspective ? params.z : 0.0;
    // In texels: a section of world radius s at distance z covers s / (params.x z) texels of a
    // perspective map.
    float searchTexels = perspective ? lightSize * (receiverDistance - nearest) / receiverDistance
                                         / (params.x * nearest)
                                     : lightSize * receiverDistance / texelWorld;
    float searchRadius = clamp(searchTexels, SHADOW_MIN_SEARCH_RADIUS_TEXELS, SHADOW_MAX_FILTER_RADIUS_TEXELS);
    float blockerDistance = 0.0, blockers = 0.0;
    vec2 direction = firstDirection;
    for (int i = 0; i < SHADOW_DISC_TAPS; ++i, direction = nextVogelDirection(direction)) {
        vec4 depths, plane;
        vec2 unused;
        gatherAgainstPlane(r, r.atlas.xy + searchRadius * vogelRadius(i) * direction, depths, plane, unused);
        vec4 blocking = vec4(lessThan(depths, plane));
        blockers += dot(blocking, vec4(1.0));
        blockerDistance += dot(blocking, viewDistancesOfDepths(params, perspective, depths));
    }
    if (blockers == 0.0) return -1.0;
    blockerDistance /= blockers;
    float gap = max(receiverDistance - blockerDistance, 0.0);
    float penumbraWorld = perspective ? lightSize * gap / max(blockerDistance, 1e-6) : lightSize * gap;
    return clamp(penumbraWorld / texelWorld, 0.0, SHADOW_MAX_FILTER_RADIUS_TEXELS);
}

// Fraction of the light reaching `position` through view `view` (a texel of it `texelWorld` world
// units there): one bilinear lookup for a light of no size, else the soft shadow's disc, whose
// taps' bilinear footprint adds a texel to its width.
float viewVisibility(uint view, bool perspective, vec3 position, vec3 normal, float texelWorld, float lightSize,
                     float turn) {
    ShadowReceiver r = shadowReceiver(view, position, normal, texelWorld);
    if (lightSize <= 0.0) return bilinearVisibility(r, r.atlas.xy);
    vec2 firstDirection = vec2(cos(turn), sin(turn));
    float radius = softShadowRadius(view, perspective, r, lightSize, texelWorld, firstDirection);
    if (radius < 0.0) return 1.0;
    return discFilter(r, radius, firstDirection);
}

// The view a shadowed light's maps see `position` through, with how a texel of it measures there.
struct ShadowLookup {
    uint view;
    bool perspective;
    float texelWorld;  // a texel's world size at the receiver
};

// A distant light's cascades (shadow.x first view, shadow.y count): the first cascade whose range
// holds the pixel's view distance; beyond the last one the light is unshadowed (false). The
// penumbra is sized in world units, so it keeps its width across cascade boundaries (only its
// texels change).
bool cascadeLookup(uvec4 shadow, float viewDistance, out ShadowLookup lookup) {
    for (uint c = 0u; c < shadow.y; ++c) {
        uint view = shadow.x + c;
        if (viewDistance <= shadowViews[view].params.y) {
            lookup = ShadowLookup(view, false, shadowViews[view].params.x);
            return true;
        }
    }
    return false;
}

// A local light's cube faces (+X, -X, +Y, -Y, +Z, -Z from shadow.x): the face of the major axis
// of the direction from the light; a texel's world size grows with the distance along it.
ShadowLookup cubeLookup(uvec4 shadow, vec3 position, vec3 lightPosition) {
    vec3 d = position - lightPosition;
    vec3 a = abs(d);
    uint face = a.x >= a.y && a.x >= a.z ? (d.x > 0.0 ? 0u : 1u)
              : a.y >= a.z               ? (d.y > 0.0 ? 2u : 3u)
                                         : (d.z > 0.0 ? 4u : 5u);
    uint view = shadow.x + face;
    return ShadowLookup(view, true, shadowViews[view].params.x * max(a.x, max(a.y, a.z)));
}

// A spot light's one map along its axis.
ShadowLookup spotLookup(uvec4 shadow, vec3 position, vec3 lightPosition, vec3 axis) {
    float distance = max(dot(position - lightPosition, axis), 0.0);
    return ShadowLookup(shadow.x, true, shadowViews[shadow.x].params.x * distance);
}

// The size the penumbra grows with: a distant light's tan(half angle); a sphere's radius (none
// with treatAsPoint); a rect's or disk's radius of the disc of its area, a cylinder's of its
// length times its diameter (none with treatAsLine) (XXX: a long rectangle's or tube's penumbra is
// as wide along both its axes).
float shadowLightSize(LightData light, uint kinds) {
    uint type = uint(light.positionType.w);
    if (hasLightType(kinds, LIGHT_DISTANT) && type == LIGHT_DISTANT) return tan(light.directionAngle.w);
    if (hasLightType(kinds, LIGHT_SPHERE) && type == LIGHT_SPHERE) return light.factors.z > 0.0 ? 0.0 : light.radiance.a;
    if (hasLightType(kinds, LIGHT_RECT) && type == LIGHT_RECT)
        return sqrt(4.0 / PI * length(cross(light.axisX.xyz, light.axisY.xyz)));
    if (hasLightType(kinds, LIGHT_DISK) && type == LIGHT_DISK) return sqrt(length(cross(light.axisX.xyz, light.axisY.xyz)));
    if (hasLightType(kinds, LIGHT_CYLINDER) && type == LIGHT_CYLINDER) return light.factors.z > 0.0 ? 0.0 : sqrt(4.0 / PI * light.radiance.a * length(light.axisX.xyz));
    return 0.0;
}

// The turn of a pixel's soft-shadow taps: interleaved gradient noise of the pixel, moved on by the
// golden ratio each frame of temporal AA's cycle (frame_data.glsl CameraData::noiseFrame).
float shadowFilterTurn(vec2 pixel, uint noiseFrame) {
    return 2.0 * PI * fract(interleavedGradientNoise(pixel) + 0.618034 * float(noiseFrame));
}

// Fraction of `light` reaching a surface point (world position and unit normal, view distance
// along the camera's axis, the soft-shadow taps' turn); 1 for lights without shadow views. `kinds`:
// the kinds of light the caller may pass (light_evaluation.glsl hasLightType).
float shadowVisibility(LightData light, vec3 position, vec3 normal, float viewDistance, float turn, uint kinds) {
    uvec4 shadow = light.shadow;
    if (shadow.y == 0u) return 1.0;
    float size = shadowLightSize(light, kinds);
    // Only the projections `kinds` holds (light_evaluation.glsl LIGHT_KINDS).
    ShadowLookup lookup;
    if (hasLightKind(kinds, LIGHT_KIND_SHADOW_CASCADES) && shadow.z == SHADOW_CASCADES) {
        if (!cascadeLookup(shadow, viewDistance, lookup)) return 1.0;
    } else if (hasLightKind(kinds, LIGHT_KIND_SHADOW_CUBE) && shadow.z == SHADOW_CUBE) {
        lookup = cubeLookup(shadow, position, light.positionType.xyz);
    } else if (hasLightKind(kinds, LIGHT_KIND_SHADOW_SPOT)) {
        lookup = spotLookup(shadow, position, light.positionType.xyz, light.directionAngle.xyz);
    } else {
        return 1.0;
    }
    // On a CPU device one filter call site for every kind of view: lavapipe compiles each inlined
    // copy of the soft-shadow filter into every light's loop body, and three copies cost it more
    // registers (and time, also for lights without shadows) than the filter's own work. A GPU
    // compiles a copy per kind with its projection known (the blocker search then linearises
    // orthographic depths without a division): 0.10 ms less lighting at 1080p on an H200, 0.2 ms
    // with per-sample lighting (bench/RESULTS.md).
    if (COMPACT_CODE)
        return viewVisibility(lookup.view, lookup.perspective, position, normal, lookup.texelWorld, size, turn);
    if (lookup.perspective) return viewVisibility(lookup.view, true, position, normal, lookup.texelWorld, size, turn);
    return viewVisibility(lookup.view, false, position, normal, lookup.texelWorld, size, turn);
}

#endif
