// Shadow lookups, per pixel (seed 000 "Deferred MSAA \ performance shortcuts": sun shadows are
// computed at pixel frequency): choose a light's view in the shadow atlas (a cascade by view
// distance, a cube face by the major axis, a spot's one map), offset the receiver along its
// normal, and filter.
//
// The includer declares, before including this file:
//   ShadowViewData shadowViews[]   the frame's views (a storage buffer, frame_data.glsl)
//   sampler2D shadowAtlas          the atlas (passes/shadow_maps.h) with a nearest-filtering sampler
#ifndef OBSCURA_SHADOW_SAMPLING_GLSL
#define OBSCURA_SHADOW_SAMPLING_GLSL

// Normal offset (Holbein 2011, "Normal offset shadows"): the receiver moves along its normal by
// this many texels of its view before the lookup, which removes the acne that depth bias alone
// leaves on surfaces at grazing angles to the light; the rasteriser's slope-scaled bias
// (passes/shadow_maps.cpp) covers the filter's footprint.
const float SHADOW_NORMAL_OFFSET_TEXELS = 1.5;

// Percentage-closer filtering (Reeves et al. 1987) with a 3x3-texel box that slides with the
// sample: over the 4x4 texels it touches, the edge texels weigh by how much of them the box
// covers (bilinear weights), so the result changes smoothly as the receiver moves. The 16 depths
// arrive in four gathers and are compared in the shader: lavapipe offers no linear filtering of
// depth formats, so no hardware comparison filtering (and four gathers cost it less than 16
// fetches). The footprint is kept inside the view's tile.
// atlasPosition: atlas texel coordinates and the receiver's depth; tileRect: the view's tile.
float percentageCloserFilter(vec3 atlasPosition, vec4 tileRect) {
    vec2 position = atlasPosition.xy - 0.5;  // texel centres at whole numbers
    vec2 base = floor(position);
    vec2 f = position - base;
    base = clamp(base, tileRect.xy + 1.0, tileRect.zw - 2.0);
    vec2 texelSize = 1.0 / vec2(textureSize(shadowAtlas, 0));
    // Texel offsets -1, 0, 1, 2 from base, along x and y.
    vec4 weightX = vec4(1.0 - f.x, 1.0, 1.0, f.x);
    vec4 weightY = vec4(1.0 - f.y, 1.0, 1.0, f.y);
    float lit = 0.0;
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
            // A gather at the corner shared by texels base + (2i - 1 .. 2i, 2j - 1 .. 2j) returns
            // them as x (left, bottom row), y (right, bottom), z (right, top), w (left, top).
            vec4 occluders = textureGather(shadowAtlas, (base + vec2(2 * i, 2 * j)) * texelSize);
            vec4 visible = step(vec4(atlasPosition.z), occluders);
            vec2 wx = vec2(weightX[2 * i], weightX[2 * i + 1]);
            vec2 wy = vec2(weightY[2 * j], weightY[2 * j + 1]);
            lit += dot(visible, vec4(wx.x * wy.y, wx.y * wy.y, wx.y * wy.x, wx.x * wy.x));
        }
    }
    return lit / 9.0;
}

// Fraction of the light reaching `position` through view `view`, sampled at the receiver moved
// `normalOffset` world units along `normal`.
float viewVisibility(uint view, vec3 position, vec3 normal, float normalOffset) {
    vec4 clip = shadowViews[view].worldToAtlas * vec4(position + normal * normalOffset, 1.0);
    return percentageCloserFilter(clip.xyz / clip.w, shadowViews[view].tileRect);
}

// A distant light's cascades (shadow.x first view, shadow.y count): the first cascade whose range
// holds the pixel's view distance; beyond the last one the light is unshadowed.
float cascadeVisibility(uvec4 shadow, vec3 position, vec3 normal, float viewDistance) {
    for (uint c = 0u; c < shadow.y; ++c) {
        uint view = shadow.x + c;
        if (viewDistance <= shadowViews[view].params.y)
            return viewVisibility(view, position, normal, shadowViews[view].params.x * SHADOW_NORMAL_OFFSET_TEXELS);
    }
    return 1.0;
}

// A local light's cube faces (+X, -X, +Y, -Y, +Z, -Z from shadow.x): the face of the major axis
// of the direction from the light; a texel's world size grows with the distance along it.
float cubeVisibility(uvec4 shadow, vec3 position, vec3 normal, vec3 lightPosition) {
    vec3 d = position - lightPosition;
    vec3 a = abs(d);
    uint face = a.x >= a.y && a.x >= a.z ? (d.x > 0.0 ? 0u : 1u)
              : a.y >= a.z               ? (d.y > 0.0 ? 2u : 3u)
                                         : (d.z > 0.0 ? 4u : 5u);
    uint view = shadow.x + face;
    float distance = max(a.x, max(a.y, a.z));
    return viewVisibility(view, position, normal, shadowViews[view].params.x * distance * SHADOW_NORMAL_OFFSET_TEXELS);
}

// A spot light's one map along its axis.
float spotVisibility(uvec4 shadow, vec3 position, vec3 normal, vec3 lightPosition, vec3 axis) {
    float distance = max(dot(position - lightPosition, axis), 0.0);
    return viewVisibility(shadow.x, position, normal, shadowViews[shadow.x].params.x * distance * SHADOW_NORMAL_OFFSET_TEXELS);
}

// Fraction of `light` reaching a surface point (world position and unit normal, view distance
// along the camera's axis); 1 for lights without shadow views.
float shadowVisibility(LightData light, vec3 position, vec3 normal, float viewDistance) {
    uvec4 shadow = light.shadow;
    if (shadow.y == 0u) return 1.0;
    if (shadow.z == SHADOW_CASCADES) return cascadeVisibility(shadow, position, normal, viewDistance);
    if (shadow.z == SHADOW_CUBE) return cubeVisibility(shadow, position, normal, light.positionType.xyz);
    return spotVisibility(shadow, position, normal, light.positionType.xyz, light.directionAngle.xyz);
}

#endif
