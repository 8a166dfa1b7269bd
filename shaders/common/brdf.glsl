// Microfacet BRDF: GGX distribution (Walter et al. 2007), height-correlated Smith visibility
// (Heitz 2014), Schlick Fresnel; Lambert diffuse. Seed 004 "Physically-based BRDFs" asks for a
// normalised, energy-consistent specular lobe; GGX is its modern form.
#ifndef OBSCURA_BRDF_GLSL
#define OBSCURA_BRDF_GLSL

const float PI = 3.14159265358979;

float ggxDistribution(float NdotH, float alpha) {
    float a2 = alpha * alpha;
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

float smithVisibilityHeightCorrelated(float NdotV, float NdotL, float alpha) {
    float a2 = alpha * alpha;
    float gv = NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2);
    float gl = NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2);
    return 0.5 / max(gv + gl, 1e-7);
}

vec3 fresnelSchlick(vec3 f0, float VdotH) {
    // A dot product of unit vectors may round past 1, and pow() of a negative base is undefined
    // (NaN on lavapipe): seen where a light sits on the line of sight (L = V, H = V).
    float f = pow(clamp(1.0 - VdotH, 0.0, 1.0), 5.0);
    return f0 + (1.0 - f0) * f;
}

// Roughness as authored (perceptual) to GGX alpha; clamped to keep highlights finite in 11-bit floats.
float alphaFromRoughness(float roughness) {
    float r = clamp(roughness, 0.045, 1.0);
    return r * r;
}

// Pre-integrated GGX for a uniform environment: scale and bias of F0 (Karis 2014, "Physically
// based shading on mobile", the analytic fit of the split-sum DFG term).
vec2 environmentBrdf(float roughness, float NdotV) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NdotV)) * r.x + r.y;
    return vec2(-1.04, 1.04) * a004 + r.zw;
}

#endif
