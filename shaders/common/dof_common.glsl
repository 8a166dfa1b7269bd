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
    float cellShare;      // the cell's linear share of the aperture (ApertureCell::share): 1 the whole
    float rotation;       // radians, the slide's theta_shutter_max
    int blades;           // 0: round
    int tapsPerSide;      // first gather pass: tapsPerSide^2 taps
    int tileNeighbourhood;  // tiles on each side whose near CoC can reach a pixel
    vec2 cellCentre;      // the part of the aperture the kernel spans: a cell of the square before
    vec2 cellHalfSize;    // the mapping (pass_support/thin_lens.h ApertureCell); (0, 0), (1, 1): all
    vec2 jitter;          // pixels the image lies shifted by (x right, y down), taken off the fields
    float pixelsPerTexel; // full-resolution pixels per field texel along each axis: 2 (half resolution) or 1
} dof;

const float DOF_PI = 3.14159265358979;

// The fields lie at half resolution (seed 000 "A plausible and efficient DOF reconstruction
// filter"), or at full resolution for a still's samples (passes/depth_of_field.h FieldResolution).
// Their CoC and tile values are stored as fractions of dof.maxRadius in R8G8 (the seed's R8G8
// CoC); the passes work with radii in field texels.
float fieldMaxRadius() { return dof.maxRadius / dof.pixelsPerTexel; }

// Tiles of the min/max CoC, in field texels (seed 000 "Tile min/max CoC"); the downsample's and
// the gather's workgroups are one tile each, which reduce the tile's values in shared memory.
const int DOF_TILE_SIZE = 8;

// The bits of a non-negative float, which order as the floats do (IEEE 754): atomicMax on a shared
// uint over them finds a workgroup's largest value exactly.
uint orderedBits(float nonNegative) { return floatBitsToUint(nonNegative); }

// Below this CoC radius (in full-resolution pixels: a CoC diameter of one pixel) a pixel is sharp.
const float DOF_SHARP_RADIUS = 0.5;

// How much of a pixel of CoC radius `radiusPixels` (full resolution) the half-resolution field
// replaces: none where the kernel (the cell's share of the CoC) spans less than DOF_SHARP_RADIUS,
// all from one field texel on. Not linear: a linear ramp over the whole CoC range mixes
// sharp and blurred copies of one surface ("signal frequency soup", seed 000 "Final composite");
// smoothstep keeps the mix short and soft-edged.
float fieldBlend(float radiusPixels) {
    return smoothstep(DOF_SHARP_RADIUS, max(dof.pixelsPerTexel, 2.0 * DOF_SHARP_RADIUS), radiusPixels * dof.cellShare);
}
// How much a pixel of near CoC radius `radiusPixels` belongs to the near field: by the whole CoC,
// whatever part of the aperture the kernel spans. A near surface is seen through the near field
// alone (what it hides shows where that field thins), so its share in the field must not depend
// on how far one frame's cell spreads it: a still's small cells would leave it half transparent.
const float DOF_NEAR_RADIUS = 2.0;
float nearFieldShare(float radiusPixels) { return smoothstep(DOF_SHARP_RADIUS, DOF_NEAR_RADIUS, radiusPixels); }

// Whether a CoC radius in field texels blurs at all: its kernel reaches beyond the sharp radius.
bool blursInField(float radiusTexels) {
    return radiusTexels * dof.pixelsPerTexel * dof.cellShare > DOF_SHARP_RADIUS;
}

// Signed CoC radius in full-resolution pixels of a device depth: positive in front of the focus
// plane (near field), negative behind it (far field), limited to dof.maxRadius.
float signedCocRadius(float depth) {
    return clamp(depth * dof.cocScale + dof.cocBias, -dof.maxRadius, dof.maxRadius);
}

// The radius the gather spreads its taps over for a CoC radius, both in field texels. The chain
// blurs by itself: at half resolution the 2x2 downscale, the bilinear taps and the bicubic B-spline
// upscale add a variance of 1/12 + 1/6 + 1/3 texel^2 per axis (7/12); at full resolution the
// bilinear taps and the bilinear read of the jitter-shifted field, 1/6 + 1/6 on average. A disc of
// radius R has R^2 / 4, so the whole aperture's kernel shrinks to keep the CoC's second moment. A
// cell's kernel does not: the frame is seen from the cell's own point of the lens, which no kernel
// moves, and the cells' kernels must meet where they join.
float kernelRadius(float cocRadius) {
    float chainVariance = dof.pixelsPerTexel > 1.0 ? 7.0 / 12.0 : 1.0 / 3.0;
    return dof.cellShare < 1.0 ? cocRadius : sqrt(max(cocRadius * cocRadius - 4.0 * chainVariance, 0.0));
}

// A gathered sample of CoC r seen from a kernel of radius R stands for (R / r)^2 of its own blur
// (scatter as gather), up to this ratio: a kernel's tap stands for no more than a sample's whole blur.
const float DOF_MAX_SPREAD = 4.0;

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
// n-gon, area-preserving), x right, y up, in the unit circle; mirrors thin_lens.cpp sampleAperture.
vec2 apertureTap(vec2 square) {
    vec2 polar = concentricDisc(square);
    if (dof.blades >= 3) {
        float halfAngle = DOF_PI / float(dof.blades);
        float local = polar.y - dof.rotation;
        float middle = 2.0 * halfAngle * floor((local + halfAngle) / (2.0 * halfAngle));
        float phi = atan(tan(halfAngle) * (local - middle) / halfAngle);
        polar = vec2(polar.x * cos(halfAngle) / cos(phi), dof.rotation + middle + phi);
    }
    return polar.x * vec2(cos(polar.y), sin(polar.y));
}

// A tap of the kernel over the cell: `grid` in [-1, 1]^2 across the cell. xy: its offset on the
// unit aperture from the point the frame looks through (the cell centre's); z: how far the cell
// reaches from that point along the tap's direction (the offset of the cell's edge beyond it),
// which a sample's own CoC must cover for its blur to arrive here; 1 for the centre tap.
vec3 cellTap(vec2 grid) {
    vec2 centre = apertureTap(dof.cellCentre);
    vec2 offset = apertureTap(dof.cellCentre + dof.cellHalfSize * grid) - centre;
    float across = max(abs(grid.x), abs(grid.y));
    float reach = across > 0.0 ? length(apertureTap(dof.cellCentre + dof.cellHalfSize * grid / across) - centre) : 1.0;
    return vec3(offset, reach);
}

// How much of a tap at `offset` (its length, texels) a sample of CoC `cocRadius` (texels) reaches,
// whose blur ends `reach` (cellTap's z) times its CoC along the tap: 1 inside, 0 beyond, ramping
// over the ring of the kernel the tap stands for (the taps lie 2/N of the reach apart), so that a
// sample's blur counts its whole ring and a cell's kernel meets its neighbour's without a seam.
float tapReach(float cocRadius, float reach, float offsetLength) {
    float edge = cocRadius * reach;
    float ring = max(2.0 * edge / float(dof.tapsPerSide), 1e-3);
    return clamp((edge - offsetLength) / ring + 0.5, 0.0, 1.0);
}

// An aperture offset (y up) in image texels (rows grow downwards).
vec2 apertureToTexels(vec2 aperture) { return vec2(aperture.x, -aperture.y); }

#endif
