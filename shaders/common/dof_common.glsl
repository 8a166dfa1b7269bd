// Shared by the depth-of-field passes (passes/depth_of_field.cpp, seed 000 "Depth of field"): the
// lens constants, the per-pixel circle of confusion and the aperture mapping of the gather taps.
// The aperture mapping mirrors pass_support/thin_lens.cpp (sampleAperture, squareGridCell), which the
// reference mode's lens sampling uses on the CPU: change them together.
#ifndef OBSCURA_DOF_COMMON_GLSL
#define OBSCURA_DOF_COMMON_GLSL

// Mirrors DofConstants in passes/depth_of_field.cpp.
layout(push_constant) uniform DofConstants {
    float cocScale;       // signed CoC radius in full-resolution pixels = depth * cocScale + cocBias
    float cocBias;        // (thin lens, one multiply-add: pass_support/thin_lens.h cocFromDepth)
    float maxRadius;      // largest CoC radius in full-resolution pixels ("limit offset range")
    float polygonBlend;   // the slide's f: 0 a round aperture, 1 the full polygon
    float rotation;       // radians, the slide's theta_shutter_max
    int blades;           // 0: round
    int tapsPerSide;      // first gather pass: tapsPerSide^2 taps
    int tileNeighbourhood;  // tiles on each side whose near CoC can reach a pixel
} dof;

const float DOF_PI = 3.14159265358979;

// Half-resolution CoC and tile values are stored as fractions of dof.maxRadius in R8G8 (seed 000
// "A plausible and efficient DOF reconstruction filter": R8G8 CoC); the passes work with radii in
// half-resolution texels.
float halfResolutionMaxRadius() { return 0.5 * dof.maxRadius; }

// Tiles of the min/max CoC, in half-resolution texels (seed 000 "Tile min/max CoC").
const int DOF_TILE_SIZE = 8;

// Below this CoC radius (in full-resolution pixels: a CoC diameter of one pixel) a pixel is sharp.
const float DOF_SHARP_RADIUS = 0.5;

// How much of a pixel of CoC radius `radiusPixels` (full resolution) the half-resolution field
// replaces: none below DOF_SHARP_RADIUS, all from one half-resolution texel on. Not linear: a
// linear ramp over the whole CoC range mixes sharp and blurred copies of one surface ("signal
// frequency soup", seed 000 "Final composite"); smoothstep keeps the mix short and soft-edged.
const float DOF_FIELD_RADIUS = 2.0;
float fieldBlend(float radiusPixels) { return smoothstep(DOF_SHARP_RADIUS, DOF_FIELD_RADIUS, radiusPixels); }

// Signed CoC radius in full-resolution pixels of a device depth: positive in front of the focus
// plane (near field), negative behind it (far field), limited to dof.maxRadius.
float signedCocRadius(float depth) {
    return clamp(depth * dof.cocScale + dof.cocBias, -dof.maxRadius, dof.maxRadius);
}

// The radius the gather spreads its taps over for a CoC radius, both in half-resolution texels.
// The half-resolution chain blurs by itself: the 2x2 downscale, the bilinear taps and the bicubic
// B-spline upscale add a variance of 1/12 + 1/6 + 1/3 texel^2 per axis (7/12). A disc of radius R
// has R^2 / 4, so the kernel shrinks to keep the CoC's second moment.
const float DOF_CHAIN_VARIANCE = 7.0 / 12.0;
float kernelRadius(float cocRadius) { return sqrt(max(cocRadius * cocRadius - 4.0 * DOF_CHAIN_VARIANCE, 0.0)); }

// Centre of cell `index` (row-major) of a side x side grid over [-1, 1]^2: the square kernel.
vec2 squareGridCell(int index, int side) {
    ivec2 cell = ivec2(index % side, index / side);
    return (2.0 * vec2(cell) + 1.0) / float(side) - 1.0;
}

// Concentric mapping (Shirley & Chiu 1997) square -> disc, as (radius, angle).
vec2 concentricDisc(vec2 square) {
    float a = square.x, b = square.y;
    if (a == 0.0 && b == 0.0) return vec2(0.0);
    if (abs(a) > abs(b)) {
        float angle = DOF_PI / 4.0 * (b / a);
        return a > 0.0 ? vec2(a, angle) : vec2(-a, angle + DOF_PI);
    }
    float angle = DOF_PI / 2.0 - DOF_PI / 4.0 * (a / b);
    return b > 0.0 ? vec2(b, angle) : vec2(-b, angle + DOF_PI);
}

// A square point on the aperture (seed 000 "Sampling": concentric mapping, then the diaphragm's
// n-gon with the f-stop interpolation): xy the offset in the unit circle (x right, y up), z the
// area the mapping gives it relative to a round aperture, so that taps weighted by z spread
// evenly over the polygon.
vec3 apertureTap(vec2 square) {
    vec2 polar = concentricDisc(square);
    float scale = 1.0;
    if (dof.blades >= 3 && dof.polygonBlend > 0.0) {
        float n = float(dof.blades);
        float sector = polar.y - (2.0 * DOF_PI / n) * floor((n * polar.y + DOF_PI) / (2.0 * DOF_PI));
        scale = pow(cos(DOF_PI / n) / cos(sector), dof.polygonBlend);
    }
    float angle = polar.y + dof.polygonBlend * dof.rotation;
    return vec3(polar.x * scale * vec2(cos(angle), sin(angle)), scale * scale);
}

// An aperture offset (y up) in image texels (rows grow downwards).
vec2 apertureToTexels(vec2 aperture) { return vec2(aperture.x, -aperture.y); }

#endif
