#version 450
// Shows one AOV of a render buffer (its pixels as the ABI lays them out: rows top to bottom,
// tightly packed) in the viewer's RGBA8 display image.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Pixels { uint words[]; };
layout(rgba8, binding = 1) uniform writeonly image2D display;

// What the pixels hold and how they are shown (harness/view/aov_display.h, AovView).
const uint kDisplay = 0u;  // unorm8Vec4, display-referred: shown as it is
const uint kDepth = 1u;    // float32 clip-space depth: near white, far black
const uint kNormal = 2u;   // float32Vec3 eye-space normal: 0.5 + 0.5 n
const uint kMotion = 3u;   // float32Vec3 pixels moved: hue by direction, brightness by length
const uint kPrimId = 4u;   // int32: a colour hashed from the id, black where nothing drew

layout(push_constant) uniform Push {
    uint view;
    uint width;
    uint height;
    float motionScale;  // pixels of motion shown at full brightness
} push;

float at(uint index) { return uintBitsToFloat(words[index]); }

vec3 idColour(int id) {
    if (id < 0) return vec3(0.0);
    uint h = uint(id) * 2654435761u;  // Knuth's multiplicative hash
    return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0 * 0.8 + 0.2;
}

void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (p.x >= push.width || p.y >= push.height) return;
    uint pixel = p.y * push.width + p.x;
    vec4 c = vec4(0.0, 0.0, 0.0, 1.0);
    if (push.view == kDisplay) {
        c = unpackUnorm4x8(words[pixel]);
        c.a = 1.0;
    } else if (push.view == kDepth) {
        float d = at(pixel);
        c.rgb = vec3(d >= 1.0 ? 0.0 : 1.0 - pow(d, 64.0));
    } else if (push.view == kNormal) {
        vec3 n = vec3(at(3u * pixel), at(3u * pixel + 1u), at(3u * pixel + 2u));
        c.rgb = dot(n, n) > 0.0 ? 0.5 + 0.5 * n : vec3(0.0);
    } else if (push.view == kMotion) {
        vec2 m = vec2(at(3u * pixel), at(3u * pixel + 1u));
        float angle = atan(m.y, m.x);
        vec3 hue = 0.5 + 0.5 * cos(angle + vec3(0.0, 2.094, 4.189));
        c.rgb = hue * clamp(length(m) / push.motionScale, 0.0, 1.0);
    } else if (push.view == kPrimId) {
        c.rgb = idColour(int(words[pixel]));
    }
    imageStore(display, ivec2(p), c);
}
