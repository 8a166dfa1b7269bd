#version 460
#extension GL_GOOGLE_include_directive : require
// SSAO step 1: volumetric obscurance (Loos & Sloan 2010) with the 4 samples of seed 004 "SSAO
// improvements", at half resolution. The half-resolution geometry is taken from the G-buffer here
// (heldPixel, ssao_common.glsl), for the texel and for each sample alike, and the texel's is
// written for the steps after: one pass where a downsample pass and its barrier came first.
// Depth is stored linear so that the obscurance works in view space; the normal is the G-buffer's
// best-fit normal of the same pixel, copied as it is, with which pixel of the 2x2 it was in alpha
// (index / 3) so that the later steps put the point exactly where it was seen. Obscurance is the fraction of a sphere of radius R around the
// surface point that lies behind the depth buffer, estimated with line integrals: each sample is
// the sphere's chord along the view ray of one texel, split where the visible surface crosses it.
// With the G-buffer normal (Loos & Sloan discuss bringing the normal in), only the part of the
// sphere in front of the tangent plane counts: a plane is then unoccluded exactly, wherever the
// samples land, a right-angled crease half occluded and a closed pit fully.
// The samples are two point-symmetric pairs of offsets in the plane through the centre
// perpendicular to the view axis, turning from pixel to pixel over 4x4 blocks
// (pass_support/ssao_pattern.cpp); the blur averages the turns back out, and the whole pattern turns from
// frame to frame so that the temporal accumulation (ssao_temporal_blur.comp) gathers new directions.
#include "common/frame_data.glsl"
#include "common/best_fit_normals.glsl"
#include "common/ssao_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

CAMERA_BLOCK(0);
layout(set = 0, binding = 1) uniform sampler2D depthTexture;  // the G-buffer's, full resolution
layout(set = 0, binding = 2) uniform sampler2D normalRoughnessTexture;
layout(set = 0, binding = 3, r32f) uniform writeonly image2D halfDepth;
layout(set = 0, binding = 4, rgba8) uniform writeonly image2D halfNormal;  // a: which pixel of the 2x2, index / 3
layout(set = 0, binding = 5, r8) uniform writeonly image2D accessibilityImage;

layout(push_constant) uniform Push {
    uint pattern[16];  // packSnorm4x8(inner pair, outer pair) per pixel of a 4x4 block, in units of R
    float radius;      // R, scene units
    float intensity;
    vec2 frameRotation;  // cos, sin: turns the whole pattern from frame to frame for the temporal accumulation
} push;

// The tangent plane sits this far (in units of R) above the surface: the best-fit normal is off by
// up to ~0.3 degrees (8-bit storage cannot hold an axis exactly), which tilts the plane by up to
// 0.006 R within the sphere and would leave flat surfaces a grain of occlusion.
const float kTangentPlaneLift = 0.01;

struct Centre {
    vec3 position;  // view space
    vec3 normal;    // view space, on the side the camera sees
};


// Line integral along the view ray of `texel`: x, the length of the sphere's chord in front of
// the tangent plane; y, how much of that lies behind the visible surface, in scene units. Zero for
// a ray that misses the sphere, and for a surface in front of the whole chord: that ray tells
// nothing about the sphere (a separate foreground object; counted as solid it would draw a dark
// halo around every silhouette). The price: solid hidden behind a surface that reaches the sphere
// is dropped too, so at grazing views the wall side of a floor-wall crease reads lighter.
vec2 chordAboveTangentPlane(Centre centre, ivec2 texel) {
    HeldPixel held = heldPixel(depthTexture, texel);
    float depth = linearDepthFromDevice(camera.projection, held.deviceDepth);
    vec2 ndc = heldPixelNdc(texel, held.index, camera.resolution);
    vec3 origin = viewPositionFromLinearDepth(camera.projection, ndc, 0.0);
    vec3 surface = viewPositionFromLinearDepth(camera.projection, ndc, depth);
    float hit = distance(surface, origin);
    vec3 direction = (surface - origin) / hit;
    vec3 toCentre = centre.position - origin;
    float closest = dot(toCentre, direction);
    vec3 miss = toCentre - closest * direction;
    float halfChordSquared = push.radius * push.radius - dot(miss, miss);
    if (halfChordSquared <= 0.0) return vec2(0.0);
    float halfChord = sqrt(halfChordSquared);
    float entry = closest - halfChord, exit = closest + halfChord;
    if (hit < entry) return vec2(0.0);
    // The ray crosses the tangent plane where dot(N, origin + t * direction - P) = 0; it is on the
    // camera's side before that when it heads into the plane, after it when it heads out.
    float heightOfOrigin = dot(centre.normal, origin - centre.position) - kTangentPlaneLift * push.radius;
    float climb = dot(centre.normal, direction);
    if (climb < 0.0) exit = min(exit, -heightOfOrigin / climb);
    else if (climb > 0.0) entry = max(entry, -heightOfOrigin / climb);
    else if (heightOfOrigin <= 0.0) return vec2(0.0);
    float upper = max(exit - entry, 0.0);
    return vec2(upper, clamp(exit - max(entry, hit), 0.0, upper));
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(accessibilityImage);
    if (any(greaterThanEqual(texel, size))) return;
    HeldPixel held = heldPixel(depthTexture, texel);
    float depth = linearDepthFromDevice(camera.projection, held.deviceDepth);
    ivec2 lastPixel = textureSize(depthTexture, 0) - 1;
    vec4 normalTexel = vec4(
        texelFetch(normalRoughnessTexture, min(texel * 2 + ivec2(held.index & 1, held.index >> 1), lastPixel), 0).rgb,
        float(held.index) / 3.0);
    imageStore(halfDepth, texel, vec4(depth));
    imageStore(halfNormal, texel, normalTexel);
    // Nothing was drawn where the depth is the far plane's (the G-buffer clears depth to 1).
    if (depth >= 0.999 * linearDepthFromDevice(camera.projection, 1.0)) {
        imageStore(accessibilityImage, texel, vec4(1.0));
        return;
    }
    vec2 ndc = heldPixelNdc(texel, held.index, camera.resolution);
    Centre centre;
    centre.position = viewPositionFromLinearDepth(camera.projection, ndc, depth);
    vec3 normal = normalize(mat3(camera.view) * decodeBestFitNormal(normalTexel.rgb));
    // Towards the eye along the pixel's ray (the origin for perspective, +z for orthographic): a
    // single-sided surface seen from behind has its normal turned to the side in view.
    vec3 towardEye = viewPositionFromLinearDepth(camera.projection, ndc, 0.0) - centre.position;
    centre.normal = faceforward(normal, -towardEye, normal);

    vec4 pairs = unpackSnorm4x8(push.pattern[(texel.y & 3) * 4 + (texel.x & 3)]);
    vec2 chords = vec2(0.0);
    for (int i = 0; i < 4; ++i) {
        vec2 offset = (i < 2 ? pairs.xy : pairs.zw) * ((i & 1) == 0 ? push.radius : -push.radius);
        offset = mat2(push.frameRotation.x, push.frameRotation.y, -push.frameRotation.y, push.frameRotation.x) * offset;
        vec4 clip = camera.projection * vec4(centre.position + vec3(offset, 0.0), 1.0);
        ivec2 sampleTexel = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * camera.resolution * 0.5));
        if (all(greaterThanEqual(sampleTexel, ivec2(0))) && all(lessThan(sampleTexel, size)))
            chords += chordAboveTangentPlane(centre, sampleTexel);
    }
    // The samples stand for equal areas of the disc (pass_support/ssao_pattern.cpp), so the chords'
    // lengths weigh the volumes: occlusion is the occupied share of the sphere's upper part.
    float occlusion = chords.x > 0.0 ? chords.y / chords.x : 0.0;
    imageStore(accessibilityImage, texel, vec4(clamp(1.0 - push.intensity * occlusion, 0.0, 1.0)));
}
