// HDR-correct resolve of MSAA samples (issue: seed 000 "MSAA \ performance shortcuts (3)": with HDR
// rendering "tone mapping is implicitly done post-resolve resulting in loss of detail on high
// contrast regions" — a plain average lets one very bright sample paint the whole pixel, and after
// tone mapping the silhouette of a bright object against a dark one grows a bright outline).
// The samples are averaged where the display sees them, after a tone map, and mapped back: with
// Reinhard's T(x) = x / (1 + luma(x)) and its inverse T'(y) = y / (1 - luma(y)),
//     T'(mean of T(x_s)) = sum(w_s x_s) / sum(w_s),  w_s = 1 / (1 + luma(x_s)),
// a weighted average in linear space (Karis 2013, "Tone mapping", the weighting Lottes proposed
// for resolves). Flat pixels (all samples alike) resolve to their value exactly. Inputs are exposed
// radiance, so luma 1 is where the display's tone curve bends. Luma: Rec.709 weights.
#ifndef OBSCURA_HDR_RESOLVE_GLSL
#define OBSCURA_HDR_RESOLVE_GLSL

float hdrResolveWeight(vec3 exposedRadiance) {
    return 1.0 / (1.0 + dot(exposedRadiance, vec3(0.2126, 0.7152, 0.0722)));
}

// The resolved radiance from the sums of w_s x_s and of w_s over a pixel's samples.
vec3 hdrResolve(vec3 weightedRadianceSum, float weightSum) {
    return weightedRadianceSum / weightSum;
}

#endif
