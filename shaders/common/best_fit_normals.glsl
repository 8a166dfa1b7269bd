// Best-fit normals (Kaplanyan 2010, seed 004 "Normals precision for shading" and appendix A):
// scale the normal so that its 8-bit quantisation lands closest to the true direction.
#ifndef OBSCURA_BEST_FIT_NORMALS_GLSL
#define OBSCURA_BEST_FIT_NORMALS_GLSL

// Appendix A, CompressUnsignedNormalToNormalsBuffer: the fitting scale comes from the 2D
// texture that holds the unique part of the symmetric best-fit cube map.
vec3 encodeBestFitNormal(vec3 n, sampler2D fittingScale) {
    n = normalize(n);
    vec3 unsignedN = abs(n);
    float maxAbs = max(unsignedN.z, max(unsignedN.x, unsignedN.y));
    vec2 uv = unsignedN.z < maxAbs ? (unsignedN.y < maxAbs ? unsignedN.yz : unsignedN.xz) : unsignedN.xy;
    uv = uv.x < uv.y ? uv.yx : uv.xy;
    uv.y /= max(uv.x, 1e-8);
    n /= maxAbs;
    n *= textureLod(fittingScale, uv, 0.0).r;
    return n * 0.5 + 0.5;
}

// Reconstruction is just a normalisation (seed 004 "Best fit for normals").
vec3 decodeBestFitNormal(vec3 stored) {
    return normalize(stored * 2.0 - 1.0);
}

#endif
