#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred MSAA custom resolve, second half (seed 000 "custom resolve & per-sample mask" and
// "stencil batching"): compares each pixel's samples and tags the 2x2 quad of a pixel whose
// samples differ in the reserved stencil bit. The pipeline writes the bit with REPLACE under the
// stencil write mask 0x80, so the clip volumes' bits survive; untagged pixels are discarded.
// (Writing stencil from a shader needs VK_EXT_shader_stencil_export, which is not core: discard
// and the stencil op do it on every device, as the seed's fallback does with clip/discard.)
#include "common/frame_data.glsl"
#include "common/msaa_samples.glsl"

layout(set = 0, binding = 0) uniform sampler2DMS depthSamples;
layout(set = 0, binding = 1) uniform sampler2DMS normalRoughnessSamples;
layout(set = 0, binding = 3) uniform usampler2DMS instanceSamples;
CAMERA_BLOCK(4);

void main() {
    // Helper invocations of quads that reach past the image's edge read its last texel.
    ivec2 pixel = min(ivec2(gl_FragCoord.xy), textureSize(instanceSamples) - 1);
    float edge = samplesMismatch(depthSamples, normalRoughnessSamples, instanceSamples, camera.projection, pixel)
                     ? 1.0
                     : 0.0;
    // Seed 000: "tag entire pixel-quad instead of just single pixel". Fine derivatives are the
    // differences inside the fragment quad, so for a 0/1 value |dFdxFine| is 1 exactly where the
    // horizontal neighbour differs: max(v, |dFdxFine(v)|) is the pair's maximum, and the same
    // vertically on that gives the quad's.
    float pair = max(edge, abs(dFdxFine(edge)));
    float quad = max(pair, abs(dFdyFine(pair)));
    if (quad < 0.5) discard;
}
