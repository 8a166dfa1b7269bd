// A textured DomeLight's environment: the latitude-longitude parameterisation, the spherical
// harmonics of its irradiance and the GGX sampling of its prefiltered specular chain. Shared by
// the prefilter passes (environment_prefilter.comp, environment_irradiance.comp) and the lighting
// pass, so the three agree on every direction. Conventions: docs/ARCHITECTURE.md "Radiometric
// conventions".
#ifndef OBSCURA_ENVIRONMENT_MAP_GLSL
#define OBSCURA_ENVIRONMENT_MAP_GLSL

#include "brdf.glsl"

// UsdLuxDomeLight's latlong layout, the OpenEXR latitude-longitude map, in the dome's frame:
// +Y is the top pole; longitude 0 looks along +Z and +pi/2 along +X; u runs from longitude +pi
// (left edge) to -pi (right edge), v from latitude +pi/2 (top row) to -pi/2 (bottom row).
vec3 latlongDirection(vec2 uv) {
    float longitude = PI * (1.0 - 2.0 * uv.x);
    float latitude = PI * (0.5 - uv.y);
    return vec3(cos(latitude) * sin(longitude), sin(latitude), cos(latitude) * cos(longitude));
}

vec2 latlongUv(vec3 direction) {
    // atan(0, 0) is undefined: the poles take longitude 0.
    float longitude = abs(direction.x) + abs(direction.z) > 0.0 ? atan(direction.x, direction.z) : 0.0;
    float latitude = asin(clamp(direction.y, -1.0, 1.0));
    return vec2(0.5 - longitude / (2.0 * PI), 0.5 - latitude / PI);
}

// --- Diffuse: irradiance from 9 spherical-harmonic coefficients ------------------------------
// Ramamoorthi & Hanrahan 2001, "An efficient representation for irradiance environment maps":
// the radiance's projection onto the real harmonics of bands 0..2 (eq. 3), each band convolved
// with the clamped cosine (A0 = pi, A1 = 2 pi / 3, A2 = pi / 4, eq. 8) gives the irradiance
// E(n) = sum A_l L_lm Y_lm(n) within about 3% for natural lighting.
const int SH_COEFFICIENTS = 9;

void shBasis(vec3 d, out float y[SH_COEFFICIENTS]) {
    y[0] = 0.282095;
    y[1] = 0.488603 * d.y;
    y[2] = 0.488603 * d.z;
    y[3] = 0.488603 * d.x;
    y[4] = 1.092548 * d.x * d.y;
    y[5] = 1.092548 * d.y * d.z;
    y[6] = 0.315392 * (3.0 * d.z * d.z - 1.0);
    y[7] = 1.092548 * d.x * d.z;
    y[8] = 0.546274 * (d.x * d.x - d.y * d.y);
}

float shCosineLobe(int coefficient) {
    return coefficient == 0 ? PI : coefficient < 4 ? 2.0 * PI / 3.0 : PI / 4.0;
}

// `irradiance` holds A_l L_lm (rgb): the convolution is done once, by the projection.
vec3 shIrradiance(vec4 irradiance[SH_COEFFICIENTS], vec3 n) {
    float y[SH_COEFFICIENTS];
    shBasis(n, y);
    vec3 e = vec3(0.0);
    for (int i = 0; i < SH_COEFFICIENTS; ++i) e += irradiance[i].rgb * y[i];
    return max(e, vec3(0.0));  // band-limited ringing may dip below zero behind bright sources
}

// --- Specular: the prefiltered chain ---------------------------------------------------------
// Mip level i of the prefiltered image holds the environment convolved with the GGX lobe of
// perceptual roughness i / (levels - 1) (Karis 2013, "Real shading in Unreal Engine 4", split
// sum: the lobe taken around N = V = R); lookups interpolate between levels linearly.
float prefilteredLod(float roughness, float lastLevel) {
    return clamp(roughness, 0.0, 1.0) * lastLevel;
}

// Van der Corput radical inverse in base 2 paired with i / n (Hammersley point set).
vec2 hammersley(uint i, uint n) {
    return vec2(float(i) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

// GGX-distributed half vector around N (Karis 2013, "ImportanceSampleGGX").
vec3 importanceSampleGgx(vec2 xi, float alpha, vec3 N) {
    float phi = 2.0 * PI * xi.x;
    float cosTheta = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
    vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 tangentX = normalize(cross(up, N));
    vec3 tangentY = cross(N, tangentX);
    return tangentX * (sinTheta * cos(phi)) + tangentY * (sinTheta * sin(phi)) + N * cosTheta;
}

#endif
