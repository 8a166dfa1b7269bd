// Coverage of a pixel (the colour AOV's premultiplied alpha): the opaque surfaces' (G-buffer)
// and the transparent surfaces' over them (passes/transparent.h: 1 - prod(1 - opacity_i), what
// the forward pass's "over" blend leaves in its coverage target). Light through both: alpha
// composites "over" as the colour does (Porter & Duff 1984).
#ifndef OBSCURA_COVERAGE_GLSL
#define OBSCURA_COVERAGE_GLSL

float compositeCoverage(float opaque, float transparent) { return 1.0 - (1.0 - opaque) * (1.0 - transparent); }

// The transparent surfaces' coverage at `pixel` (passes/transparent.h). A frame without any reads
// one texel of 0 instead of a cleared full-size target: clamped to the image.
float transparentCoverageAt(sampler2D coverage, ivec2 pixel) {
    return texelFetch(coverage, min(pixel, textureSize(coverage, 0) - 1), 0).r;
}

// A pixel's coverage in a frame: a G-buffer surface (the device depth short of the far plane the
// G-buffer clears to) or a dome the camera sees (CameraData::backdropCoverage), with the
// transparent surfaces over it.
float pixelCoverage(float deviceDepth, float backdropCoverage, float transparent) {
    return compositeCoverage(max(deviceDepth < 1.0 ? 1.0 : 0.0, backdropCoverage), transparent);
}

#endif
