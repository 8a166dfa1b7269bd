// Bicubic B-spline filtering from four bilinear fetches (Sigg & Hadwiger 2005, "Fast third-order
// texture filtering", GPU Gems 2 ch. 20): the 16 weights of a cubic B-spline factor into two
// per axis, each pair folded into one linear fetch at a shifted position.
#ifndef OBSCURA_BICUBIC_GLSL
#define OBSCURA_BICUBIC_GLSL

struct BicubicTaps {
    vec2 uv[4];       // normalised coordinates for a linear-filtering sampler
    float weight[4];  // sum to 1
};

// `position`: texel coordinates (texel centres at integer + 0.5) in a texture of `size` texels.
BicubicTaps bicubicBSplineTaps(vec2 position, vec2 size) {
    vec2 x = position - 0.5;
    vec2 base = floor(x);
    vec2 f = x - base;
    vec2 f2 = f * f, f3 = f2 * f;
    vec2 w0 = (1.0 - 3.0 * f + 3.0 * f2 - f3) / 6.0;
    vec2 w1 = (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0;
    vec2 w2 = (1.0 + 3.0 * f + 3.0 * f2 - 3.0 * f3) / 6.0;
    vec2 w3 = f3 / 6.0;
    vec2 g0 = w0 + w1, g1 = w2 + w3;
    // Texel-centre coordinates of the two folded fetches per axis, then normalised.
    vec2 h0 = (base - 1.0 + w1 / g0 + 0.5) / size;
    vec2 h1 = (base + 1.0 + w3 / g1 + 0.5) / size;
    BicubicTaps taps;
    taps.uv[0] = vec2(h0.x, h0.y);
    taps.uv[1] = vec2(h1.x, h0.y);
    taps.uv[2] = vec2(h0.x, h1.y);
    taps.uv[3] = vec2(h1.x, h1.y);
    taps.weight[0] = g0.x * g0.y;
    taps.weight[1] = g1.x * g0.y;
    taps.weight[2] = g0.x * g1.y;
    taps.weight[3] = g1.x * g1.y;
    return taps;
}

#endif
