// Shared by the motion blur passes (passes/motion_blur.cpp; seed 000 "Reconstruction filter for
// plausible MB [McGuire12]" and "An improved reconstruction filter").
#ifndef OBSCURA_MOTION_BLUR_COMMON_GLSL
#define OBSCURA_MOTION_BLUR_COMMON_GLSL

// Mirrors MotionBlurConstants in passes/motion_blur.cpp.
layout(push_constant) uniform MotionBlurConstants {
    float maxRadius;      // the longest half-velocity in pixels (passes/motion_blur.h motionBlurMaxRadius)
    float spanScale;      // gather: the taps cover [-1, 1] x spanScale x the tile's neighbour max
    int samples;          // gather: taps per pass
    float softDepth;      // soft depth comparison extent, as a fraction of the centre's depth
} motionBlur;

// Tiles of the max velocity (McGuire 2012: k x k pixels, k his largest blur radius; longer blurs
// reach across more tiles, motion_blur_neighbour_max.comp).
const int MOTION_BLUR_TILE_SIZE = 32;

#endif
