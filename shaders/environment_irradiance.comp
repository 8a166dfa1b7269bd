#version 460
#extension GL_GOOGLE_include_directive : require
// A textured dome's irradiance as 9 spherical-harmonic coefficients (Ramamoorthi & Hanrahan
// 2001): the radiance of one source mip projected onto the harmonics of bands 0..2, each texel
// weighted by its exact solid angle, then convolved with the clamped cosine. One workgroup: the
// mip holds at most 256x128 texels, and this runs only when the dome's texture changes.
#include "common/environment_map.glsl"

const uint THREADS = 64u;
layout(local_size_x = THREADS) in;

layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1, std430) writeonly buffer Irradiance { vec4 irradiance[SH_COEFFICIENTS]; };

layout(push_constant) uniform Push { int level; } push;

shared vec3 partial[THREADS][SH_COEFFICIENTS];

void main() {
    uint thread = gl_LocalInvocationIndex;
    ivec2 size = textureSize(source, push.level);
    vec3 sum[SH_COEFFICIENTS];
    for (int k = 0; k < SH_COEFFICIENTS; ++k) sum[k] = vec3(0.0);
    for (uint i = thread; i < uint(size.x * size.y); i += THREADS) {
        ivec2 texel = ivec2(int(i) % size.x, int(i) / size.x);
        vec2 uv = (vec2(texel) + 0.5) / vec2(size);
        // A texel spans 2 pi / width in longitude and its row's band of latitude:
        // solid angle = (2 pi / width) (sin(top latitude) - sin(bottom latitude)).
        float top = PI * (0.5 - float(texel.y) / float(size.y));
        float bottom = PI * (0.5 - float(texel.y + 1) / float(size.y));
        float solidAngle = 2.0 * PI / float(size.x) * (sin(top) - sin(bottom));
        vec3 radiance = texelFetch(source, texel, push.level).rgb * solidAngle;
        float y[SH_COEFFICIENTS];
        shBasis(latlongDirection(uv), y);
        for (int k = 0; k < SH_COEFFICIENTS; ++k) sum[k] += radiance * y[k];
    }
    for (int k = 0; k < SH_COEFFICIENTS; ++k) partial[thread][k] = sum[k];
    barrier();
    if (thread < uint(SH_COEFFICIENTS)) {
        vec3 total = vec3(0.0);
        for (uint t = 0u; t < THREADS; ++t) total += partial[t][thread];
        irradiance[thread] = vec4(total * shCosineLobe(int(thread)), 0.0);
    }
}
