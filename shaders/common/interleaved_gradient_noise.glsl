// Interleaved gradient noise (Jimenez 2014, "Next generation post processing in Call of Duty:
// Advanced Warfare"): a value in [0, 1) per pixel whose neighbours differ as much as possible, so a
// small blur or temporal accumulation averages it out.
#ifndef OBSCURA_INTERLEAVED_GRADIENT_NOISE_GLSL
#define OBSCURA_INTERLEAVED_GRADIENT_NOISE_GLSL

float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

#endif
