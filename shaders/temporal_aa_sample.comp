#version 460
#extension GL_GOOGLE_include_directive : require
// Frame step 9, a still's sample before the mean (passes/temporal_aa.h addTemporalAaSamplePass):
// the light accumulation with the frame's coverage in alpha, as temporal AA accumulates it, so that
// motion blur over the sample's stratum of the shutter blurs the coverage along with the colour.
#include "common/frame_data.glsl"
#include "common/coverage.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D hdrColor;
layout(set = 0, binding = 1) uniform sampler2D depthTexture;
layout(set = 0, binding = 2) uniform sampler2D transparentCoverage;  // passes/transparent.h
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D sampleColor;
CAMERA_BLOCK(4);

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(sampleColor)))) return;
    float coverage = pixelCoverage(texelFetch(depthTexture, pixel, 0).r, camera.backdropCoverage,
                                   transparentCoverageAt(transparentCoverage, pixel));
    imageStore(sampleColor, pixel, vec4(texelFetch(hdrColor, pixel, 0).rgb, coverage));
}
