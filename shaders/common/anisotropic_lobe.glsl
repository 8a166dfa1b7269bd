// Anisotropic deferred materials (seed 004 "Anisotropic deferred materials", parts I and II,
// "Extracting the principal Phong lobe"): the thin G-buffer holds one normal and one gloss, which
// define a single isotropic lobe, so the G-buffer pass replaces a stretched GGX lobe by the
// isotropic lobe that best matches it under the lights that reach the pixel. The lighting pass
// then lights that lobe as any other: no G-buffer bits, no lighting-pass variant.
//
// The talk fits the NDF with spherical Gaussians [WRGSG09], convolves them with the lights' SGs
// and keeps the principal lobe. Here each light is one lobe of the lighting distribution (its
// direction, its angular radius, its irradiance), and the fit is closed-form in GGX's own slope
// space rather than through an SG sum:
//   anisotropic GGX (Burley 2012, "Physically-based shading at Disney"; Heitz 2014, "Understanding
//   the masking-shadowing function": its anisotropic GGX and Lambda), slopes s = (H.X, H.Y) / (H.N):
//       D(H) = 1 / (pi ax ay (H.N)^4 (1 + q^2)^2),   q^2 = sx^2 / ax^2 + sy^2 / ay^2
//   isotropic GGX about a normal N' at angle t' from H: the same with q = tan(t') / a'.
// Per light, with the lighting pass's widening of an extended source (w = sinHalfAngle / 2: the
// lobe's alpha grows by w, light_evaluation.glsl ggxLobe, Karis 2013) applied to each axis:
//   gloss:  a' such that the widened isotropic lobe's peak equals the widened anisotropic one's,
//           (a' + w)^2 = (ax + w)(ay + w) (a' = sqrt(ax ay) for a point: the NDF's peak and solid
//           angle kept);
//   normal: N' on the great circle through H and N, at tan(t') = q (a' + w) from H, so the
//           isotropic lobe sends the light's direction exactly the anisotropic lobe's value
//           (up to the ratio of the lobes' (H.N)^4 terms: under a point-like light the extracted
//           image is within 1.1 dB of the isotropic lobe's own PSNR, tests/delegate/anisotropic_material_test.cpp).
// The lights' lobes are merged as the talk merges SG products: N' and a' averaged with the
// radiance each light's anisotropic lobe reflects, E D(H) / (4 N.V) (Fresnel and masking are
// applied later, by the lighting pass, as the talk defers them). A dome lights the whole
// hemisphere: it pulls towards the unbent normal and the mean gloss.
//
// The includer declares the frame's lights as the lighting pass does: a storage buffer with
// `uint lightCount` and `LightData lights[]`.
#ifndef OBSCURA_ANISOTROPIC_LOBE_GLSL
#define OBSCURA_ANISOTROPIC_LOBE_GLSL

#include "light_evaluation.glsl"

// MaterialX Standard Surface's mapping (mx_roughness_anisotropy, Burley 2012): GGX alpha along the
// stretched direction X and across it (Y), from the lighting pass's alpha of the roughness.
vec2 anisotropicAlpha(float roughness, float anisotropy) {
    float alpha = alphaFromRoughness(roughness);
    float aspect = sqrt(1.0 - min(anisotropy, 0.98));
    return vec2(min(alpha / aspect, 1.0), alpha * aspect);
}

// The isotropic alpha a' whose lobe widened by w peaks as high as the anisotropic lobe widened by
// w on each axis (peak match above): (a' + w)^2 = (ax + w)(ay + w).
float peakMatchedAlpha(vec2 wide, float w) { return max(sqrt(wide.x * wide.y) - w, 0.0); }

struct LobeSum {
    vec3 normal;  // sum of weight x bent normal
    float alpha;  // sum of weight x gloss
    float weight;
};

// Adds one light seen in direction L with irradiance `irradiance` (at normal incidence) and
// angular radius asin(sinHalfAngle) to the fit.
void addLightLobe(inout LobeSum sum, vec3 N, vec3 X, vec3 Y, vec3 V, vec2 alpha, vec3 L, float irradiance,
                  float sinHalfAngle) {
    if (dot(N, L) <= 0.0 || irradiance <= 0.0) return;
    vec3 H = normalize(L + V);
    float NdotH = dot(N, H);
    if (NdotH <= 1e-4) return;
    float w = 0.5 * sinHalfAngle;
    vec2 wide = min(alpha + w, vec2(1.0));
    vec2 slope = vec2(dot(H, X), dot(H, Y)) / NdotH;
    float q2 = dot(slope / wide, slope / wide);
    float isoAlpha = peakMatchedAlpha(wide, w);
    // The widened anisotropic lobe at H.
    float NdotH2 = NdotH * NdotH;
    float D = 1.0 / (PI * wide.x * wide.y * NdotH2 * NdotH2 * (1.0 + q2) * (1.0 + q2));
    float weight = irradiance * D / (4.0 * max(dot(N, V), 1e-4));
    // N' at angle t' from H towards N (past N where the anisotropic lobe is the narrower one).
    vec3 towardN = N - H * NdotH;
    float along = length(towardN);
    float tPrime = atan(sqrt(q2) * min(isoAlpha + w, 1.0));
    vec3 bent = along > 1e-6 ? H * cos(tPrime) + towardN * (sin(tPrime) / along) : N;
    sum.normal += weight * bent;
    sum.alpha += weight * isoAlpha;
    sum.weight += weight;
}

float luminance(vec3 rgb) { return dot(rgb, vec3(0.2126, 0.7152, 0.0722)); }  // Rec. 709

// The normal and roughness of the isotropic lobe that stands for the anisotropic one at P (unit
// normal N, tangent frame from the interpolated mesh tangent, unit direction to the eye V).
// `roughness` and the result are perceptual, as the G-buffer stores them.
void principalLobe(inout vec3 N, inout float roughness, vec4 tangent, vec2 anisotropy, vec3 P, vec3 V) {
    // The tangent frame: the mesh's direction of increasing u (Lengyel 2001, made at load), re-
    // orthogonalised to the shading normal, turned by the rotation about N.
    vec3 T = tangent.xyz - N * dot(N, tangent.xyz);
    if (dot(T, T) < 1e-12) T = abs(N.x) < 0.9 ? cross(N, vec3(1.0, 0.0, 0.0)) : cross(N, vec3(0.0, 1.0, 0.0));
    T = normalize(T);
    vec3 B = cross(N, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
    vec3 X = cos(anisotropy.y) * T + sin(anisotropy.y) * B;
    vec3 Y = cos(anisotropy.y) * B - sin(anisotropy.y) * T;
    vec2 alpha = anisotropicAlpha(roughness, anisotropy.x);

    LobeSum sum = LobeSum(vec3(0.0), 0.0, 0.0);
    for (uint i = 0u; i < lightCount; ++i) {
        LightData light = lights[i];
        if (!lightReaches(light, P)) continue;
        if (uint(light.positionType.w) == LIGHT_CYLINDER) light = cylinderSeenFrom(light, P);
        float specular = light.factors.y;
        uint type = uint(light.positionType.w);
        if (type == LIGHT_DISTANT || type == LIGHT_SPHERE) {
            DirectionalSource source = directionalSource(light, P, LIGHT_KINDS);
            addLightLobe(sum, N, X, Y, V, alpha, source.L, specular * luminance(source.irradiance),
                         source.sinHalfAngle);
        } else if (type == LIGHT_RECT || type == LIGHT_DISK) {
            vec3 centre = light.positionType.xyz - P;
            if (dot(centre, light.directionAngle.xyz) >= 0.0) continue;  // behind the emitting face
            // Its solid angle as the lighting pass measures it (|vector form factor| / 2), as a
            // cone seen towards its centre.
            vec3 formFactor, clipped;
            areaLightFormFactors(light, centre, N, formFactor, clipped);
            float solidAngle = 0.5 * length(formFactor);
            float shaping = shapingAttenuation(light, normalize(-centre));
            addLightLobe(sum, N, X, Y, V, alpha, normalize(centre),
                         specular * shaping * luminance(light.radiance.rgb) * solidAngle,
                         clamp(sqrt(solidAngle / PI), 0.0, 1.0));
        } else {
            // A dome: the reflected radiance of a lobe under uniform light is about the light's
            // radiance, whichever the lobe's shape; its principal direction is the normal's.
            float weight = specular * luminance(light.radiance.rgb);
            sum.normal += weight * N;
            sum.alpha += weight * sqrt(alpha.x * alpha.y);
            sum.weight += weight;
        }
    }
    float meanAlpha = sum.weight > 0.0 ? sum.alpha / sum.weight : sqrt(alpha.x * alpha.y);
    roughness = sqrt(meanAlpha);
    // A normal turned away from the eye would leave the pixel unlit: keep the surface's there.
    vec3 bent = sum.weight > 0.0 ? sum.normal : N;
    if (dot(bent, bent) > 1e-12 && dot(normalize(bent), V) > 1e-3) N = normalize(bent);
}

#endif
