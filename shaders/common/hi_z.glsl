// The depth pyramid of GPU occlusion culling (passes/hi_z.h): level l >= 1 holds, per texel, the
// farthest device depth of the 2^l x 2^l pixels it covers, ceil(size / 2^l) texels a side, every
// level one after the other in one float buffer. Level 0 (the pixels themselves) is not stored:
// level 1 is read where a box covers at most two pixels a side.
#ifndef OBSCURA_HI_Z_GLSL
#define OBSCURA_HI_Z_GLSL

// Texels of `level` along a side of `pixels`.
uvec2 hiZLevelSize(uvec2 pixels, uint level) { return (pixels + (1u << level) - 1u) >> level; }

// The level of a single texel (at least 1).
uint hiZTopLevel(uvec2 pixels) {
    uint longest = max(pixels.x, pixels.y);
    return longest <= 2u ? 1u : uint(findMSB(longest - 1u)) + 1u;
}

// Where `level` starts in the buffer.
uint hiZLevelOffset(uvec2 pixels, uint level) {
    uint offset = 0u;
    for (uint l = 1u; l < level; ++l) {
        uvec2 size = hiZLevelSize(pixels, l);
        offset += size.x * size.y;
    }
    return offset;
}

#endif
