#version 460
// Tone mapping to display: filmic curve (ACES fit, Narkowicz 2015) and the sRGB transfer
// function, written to an 8-bit image. The accumulation is already exposed.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, r11f_g11f_b10f) uniform readonly image2D hdrColor;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D displayColor;
layout(set = 0, binding = 2) uniform usampler2D instanceTexture;

vec3 acesFilmic(vec3 x) {
    const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

vec3 srgbEncode(vec3 linear) {
    bvec3 low = lessThanEqual(linear, vec3(0.0031308));
    vec3 hi = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, linear * 12.92, low);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(displayColor);
    if (any(greaterThanEqual(pixel, size))) return;
    vec3 hdr = imageLoad(hdrColor, pixel).rgb;
    float alpha = texelFetch(instanceTexture, pixel, 0).r != 0u ? 1.0 : 0.0;
    imageStore(displayColor, pixel, vec4(srgbEncode(acesFilmic(hdr)), alpha));
}
