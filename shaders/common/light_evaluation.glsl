// Radiance one UsdLux light reflects off a G-buffer surface towards the eye. Conventions
// (docs/ARCHITECTURE.md "Lights"): radiance, irradiance and solid angles follow UsdLux; the
// host-side packing is delegate/prims/light.cpp.
#ifndef OBSCURA_LIGHT_EVALUATION_GLSL
#define OBSCURA_LIGHT_EVALUATION_GLSL

#include "frame_data.glsl"
#include "brdf.glsl"

// The kinds of light the frame holds (passes/frame_data.h lightKind), a specialization constant:
// the lighting and transparent passes build their pipelines for them, leaving out the code of the
// kinds the frame lacks (a CPU device runs every branch for every lane, taken or not: each light's
// loop iteration paid for every type and shadow projection); the G-buffer's anisotropic lobe keeps
// all of them.
layout(constant_id = 2) const uint LIGHT_KINDS = 0xffffffffu;
const uint LIGHT_KIND_SHADOW_CASCADES = 1u << 8u;
const uint LIGHT_KIND_SHADOW_CUBE = 1u << 9u;
const uint LIGHT_KIND_SHADOW_SPOT = 1u << 10u;
const uint LIGHT_KIND_SHAPED = 1u << 12u;
const uint LIGHT_KIND_TEXTURED_DOME = 1u << 13u;

// The kinds of light sorted into each of the lighting pass's loops (the light buffer holds the
// distant lights first, then the domes, then the local lights: delegate/frame_scene_builder.cpp).
const uint DISTANT_LIGHT_KINDS = (1u << LIGHT_DISTANT) | LIGHT_KIND_SHADOW_CASCADES;
const uint DOME_LIGHT_KINDS = (1u << LIGHT_DOME) | LIGHT_KIND_TEXTURED_DOME;
const uint LOCAL_LIGHT_KINDS = ~(DISTANT_LIGHT_KINDS | DOME_LIGHT_KINDS);

// Whether `kinds` (LIGHT_KINDS, narrowed by a caller that knows which lights it meets) holds a
// light of type `type` (LIGHT_*), or the kind bit `kind`. Functions take the kinds their caller
// may meet, so a loop over the distant lights compiles the distant lights' code alone.
bool hasLightType(uint kinds, uint type) { return (kinds & (1u << type)) != 0u; }
bool hasLightKind(uint kinds, uint kind) { return (kinds & kind) != 0u; }

// The textured dome's radiance as this point sees it, before the light's intensity, exposure and
// colour: irradiance / pi around N (what a white Lambert surface reflects) and the prefiltered
// radiance along the mirror direction at the base and coat roughness. A constant dome is 1 in all.
struct EnvironmentSample {
    vec3 diffuse;
    vec3 specular;
    vec3 coat;
};

struct SurfacePoint {
    vec3 P;           // world position
    vec3 N;           // unit normal
    vec3 V;           // unit direction to the eye
    vec3 diffuse;     // diffuse albedo (metallic workflow: diffuseColor x (1 - metallic))
    vec3 f0;          // specular reflectance at normal incidence
    float roughness;  // perceptual, as authored
    float clearcoat;  // UsdPreviewSurface's second specular lobe: weight and roughness
    float clearcoatRoughness;
    float ambientAccess;  // SSAO and the material's occlusion: applied to the dome only (seed 004, "SSAO":
                          // ambient light only); ambientAccessWithOcclusion
    EnvironmentSample environment;  // what the textured dome sends this point, if there is one
    float shadowTurn;  // the turn of its soft-shadow taps (shadow_sampling.glsl shadowFilterTurn)
};

// UsdPreviewSurface (https://openusd.org/release/spec_usdpreviewsurface.html): the metallic
// workflow reflects ((ior - 1) / (ior + 1))^2 at normal incidence as a dielectric and its base
// colour as a metal; the specular workflow takes specularColor as F0 and keeps diffuseColor whole.
SurfacePoint surfaceFromMaterial(MaterialData mat, vec3 baseColor, float metallic) {
    SurfacePoint s;
    float r = (mat.specularIor.a - 1.0) / (mat.specularIor.a + 1.0);
    bool specularWorkflow = mat.clearcoat.z > 0.5;
    s.f0 = specularWorkflow ? mat.specularIor.rgb : mix(vec3(r * r), baseColor, metallic);
    s.diffuse = specularWorkflow ? baseColor : (1.0 - metallic) * baseColor;
    s.clearcoat = mat.clearcoat.x;
    s.clearcoatRoughness = mat.clearcoat.y;
    return s;
}

// UsdPreviewSurface `occlusion` is "used to darken indirect lighting" (the spec,
// https://openusd.org/release/spec_usdpreviewsurface.html): baked visibility of the ambient light,
// like SSAO's. Both estimate the same quantity (the crease the asset's bake sees is also the one
// SSAO sees on screen), so the darker estimate wins: a product would darken such a crease twice
// (the baked 0.5 under SSAO's 0.5 would give 0.25), while the minimum keeps the stronger of two
// estimates that each may miss what the other sees (SSAO: off-screen and sub-pixel occluders;
// the bake: the neighbours in this scene).
float ambientAccessWithOcclusion(float screenSpaceAccess, float materialOcclusion) {
    return min(screenSpaceAccess, materialOcclusion);
}

const float CLEARCOAT_F0 = 0.04;  // the coat is a dielectric of ior 1.5

vec3 diffuseBrdf(SurfacePoint s) {
    return s.diffuse / PI;
}

// GGX lobe for light from L. A source of angular radius asin(sinHalfAngle) widens the lobe to
// alpha' = alpha + sinHalfAngle / 2 (Karis 2013, "Real shading in Unreal Engine 4": the source's
// disc seen in half-vector space), evaluated towards the source's centre: the widened NDF still
// integrates to one, so it spreads the source's light rather than dimming it (a mirror shows the
// sphere's own radiance). Karis's (alpha / alpha')^2 normalisation belongs with the other form,
// the representative point, whose NDF keeps the surface's own alpha; applied on top of the
// widening it counted the widening twice and darkened the highlights of smooth surfaces by that
// factor (to a fifth at roughness 0.2 under a sphere of angular radius 0.1).
vec3 ggxLobe(SurfacePoint s, vec3 L, float sinHalfAngle, float roughness, vec3 f0) {
    float NdotL = max(dot(s.N, L), 0.0);
    float NdotV = max(dot(s.N, s.V), 1e-4);
    vec3 H = normalize(L + s.V);
    float NdotH = max(dot(s.N, H), 0.0);
    float VdotH = max(dot(s.V, H), 0.0);
    float alpha = alphaFromRoughness(roughness);
    float alphaWide = clamp(alpha + 0.5 * sinHalfAngle, 0.0, 1.0);
    return ggxDistribution(NdotH, alphaWide) * smithVisibilityHeightCorrelated(NdotV, NdotL, alpha) *
           fresnelSchlick(f0, VdotH);
}

// What the coat lets through to the base layer (its Fresnel reflection seen from the eye).
float clearcoatTransmission(SurfacePoint s) {
    return 1.0 - s.clearcoat * fresnelSchlick(vec3(CLEARCOAT_F0), max(dot(s.N, s.V), 0.0)).x;
}

// Base and coat specular lobes, the base already attenuated by the coat.
vec3 specularBrdf(SurfacePoint s, vec3 L, float sinHalfAngle) {
    vec3 base = ggxLobe(s, L, sinHalfAngle, s.roughness, s.f0) * clearcoatTransmission(s);
    if (s.clearcoat <= 0.0) return base;
    return base + s.clearcoat * ggxLobe(s, L, sinHalfAngle, s.clearcoatRoughness, vec3(CLEARCOAT_F0));
}

// A small source of irradiance `irradiance` (at normal incidence) in direction L.
vec3 reflectFromDirection(SurfacePoint s, vec3 L, vec3 irradiance, float sinHalfAngle, vec2 factors) {
    float NdotL = dot(s.N, L);
    if (NdotL <= 0.0) return vec3(0.0);
    return (diffuseBrdf(s) * clearcoatTransmission(s) * factors.x + specularBrdf(s, L, sinHalfAngle) * factors.y) *
           irradiance * NdotL;
}

// UsdLuxShapingAPI: the cone cuts emission beyond its angle off the axis and fades it over the
// softness fraction inside; focus is a power of the cosine off the axis
// (https://openusd.org/release/user_guides/schemas/usdLux/ShapingAPI.html). A cone of 90 degrees
// or more leaves the light unshaped.
float shapingAttenuation(LightData light, vec3 fromLight) {
    if (!hasLightKind(LIGHT_KINDS, LIGHT_KIND_SHAPED)) return 1.0;
    float cosOffAxis = dot(light.directionAngle.xyz, fromLight);
    float attenuation = light.shaping.z > 0.0 ? pow(max(cosOffAxis, 0.0), light.shaping.z) : 1.0;
    float cutoff = light.shaping.x;
    if (cutoff < 0.5 * PI) {
        float offAxis = acos(clamp(cosOffAxis, -1.0, 1.0));
        float smoothStart = light.shaping.y;
        attenuation *= offAxis > cutoff ? 0.0 : (smoothStart < cutoff ? 1.0 - smoothstep(smoothStart, cutoff, offAxis) : 1.0);
    }
    return attenuation;
}

// --- Polygonal area lights --------------------------------------------------------------------
// Diffuse: the exact irradiance of a uniform polygon (Lambert 1760; the edge-integral form of
// Arvo 1995, "Applications of irradiance tensors"): E = L/2 * sum_i theta_i (N . gamma_i), the
// polygon clipped to the receiver's horizon. Specular: the representative point (Karis 2013,
// "Real shading in Unreal Engine 4") with the lobe widened by the light's solid angle.

const int DISK_POLYGON_SIDES = 16;

// theta * gamma for the edge (a, b) seen from the origin: the edge's contribution to the vector
// form factor. atan2 keeps small edges accurate where acos(dot) would not.
vec3 edgeIntegral(vec3 a, vec3 b) {
    a = normalize(a);
    b = normalize(b);
    vec3 c = cross(a, b);
    float s = length(c);
    if (s < 1e-12) return vec3(0.0);
    return c * (atan(s, dot(a, b)) / s);
}

int areaLightCorners(LightData light) { return uint(light.positionType.w) == LIGHT_RECT ? 4 : DISK_POLYGON_SIDES; }

// Corner i of the light's polygon relative to the shaded point, counter-clockwise about local +Z.
// A disk is the regular 16-gon of its area (radius scaled by sqrt(2 pi / (n sin(2 pi / n)))), so
// the irradiance of distant points is exact; on the axis it is within 0.004% at any distance.
vec3 areaLightCorner(LightData light, vec3 centre, int i) {
    if (uint(light.positionType.w) == LIGHT_RECT) {
        vec2 corner = vec2((i == 1 || i == 2) ? 1.0 : -1.0, i >= 2 ? 1.0 : -1.0);
        return centre + corner.x * light.axisX.xyz + corner.y * light.axisY.xyz;
    }
    const float areaScale = 1.01300;
    float phi = 2.0 * PI * float(i) / float(DISK_POLYGON_SIDES);
    return centre + areaScale * (cos(phi) * light.axisX.xyz + sin(phi) * light.axisY.xyz);
}

// Half the diagonal of a rect (of a disk's bounding square): how far its farthest points lie from
// its centre where its axes are perpendicular.
float areaLightHalfDiagonal(LightData light) { return length(vec2(length(light.axisX.xyz), length(light.axisY.xyz))); }

// Beyond this many half diagonals a rect or disk is lit as a point Lambert emitter of its area
// (areaLightFormFactors). Against the exact integral, over random rects, tilts and receivers at
// that distance, the point form errs by at most 0.25% where both cosines exceed 1/4, and nowhere,
// the horizon's band included (where the exact integral clips the polygon and the point form the
// cosine), by more than 0.3% of what the light turned to face the receiver gives it. The exact loop costs
// 4 or 16 edges' arc tangents; most pixels a small light reaches lie this far from it, and this is
// what bounds the lighting pass over many lights (bench/RESULTS.md).
const float AREA_LIGHT_FAR_FIELD = 32.0;

// The vector form factor sum_i theta_i gamma_i of the light's polygon (whole: the polygon's;
// clipped: its part above the horizon of normal N, Sutherland-Hodgman one edge at a time: the
// polygons are convex, so the clipped one leaves the horizon once and comes back once, closed by a
// segment along it), both oriented towards the light (a mirroring transform reverses the corners'
// order). Corners are made on the fly: no arrays, which CPU Vulkan drivers would keep in memory.
// In the far field (AREA_LIGHT_FAR_FIELD) both are the point emitter's: twice its projected solid
// angle A cos(emitter) / d^2 along the direction to its centre, clipped by the receiver's cosine
// where the caller takes the dot product with N. No edge is visited there: a CPU device's loop
// ends once all its lanes are far, where a second code path would run beside the loop.
void areaLightFormFactors(LightData light, vec3 centre, vec3 N, out vec3 whole, out vec3 clipped) {
    whole = vec3(0.0);
    clipped = vec3(0.0);
    float distance = length(centre);
    bool farField = areaLightHalfDiagonal(light) * AREA_LIGHT_FAR_FIELD < distance;
    int count = farField ? 0 : areaLightCorners(light);
    vec3 a = areaLightCorner(light, centre, 0), exitPoint = vec3(0.0), entryPoint = vec3(0.0);
    bool crossed = false;
    for (int i = 0; i < count; ++i) {
        vec3 b = areaLightCorner(light, centre, (i + 1) % count);
        vec3 edge = edgeIntegral(a, b);
        whole += edge;
        float da = dot(N, a), db = dot(N, b);
        if (da >= 0.0 && db >= 0.0) {
            clipped += edge;
        } else if (da >= 0.0 || db >= 0.0) {
            vec3 x = mix(a, b, da / (da - db));
            if (da >= 0.0) {
                clipped += edgeIntegral(a, x);
                exitPoint = x;
            } else {
                clipped += edgeIntegral(x, b);
                entryPoint = x;
            }
            crossed = true;
        }
        a = b;
    }
    if (crossed) clipped += edgeIntegral(exitPoint, entryPoint);
    // A polygon wholly below the horizon sums to zero when clipped.
    float winding = dot(whole, light.directionAngle.xyz) > 0.0 ? -1.0 : 1.0;
    whole *= winding;
    clipped *= winding;
    if (farField) {
        // The rect's parallelogram 4 |X x Y|, the disk's ellipse pi |X x Y| (its 16-gon's area).
        float area = (uint(light.positionType.w) == LIGHT_RECT ? 4.0 : PI) *
                     length(cross(light.axisX.xyz, light.axisY.xyz));
        vec3 toLight = centre / distance;
        float projectedSolidAngle = area * max(-dot(toLight, light.directionAngle.xyz), 0.0) / (distance * distance);
        whole = clipped = 2.0 * projectedSolidAngle * toLight;
    }
}

vec3 reflectFromAreaLight(SurfacePoint s, LightData light) {
    vec3 axis = light.directionAngle.xyz;
    vec3 toPoint = s.P - light.positionType.xyz;
    if (dot(toPoint, axis) <= 0.0) return vec3(0.0);  // behind the emitting face
    vec3 formFactor, clippedFormFactor;
    areaLightFormFactors(light, light.positionType.xyz - s.P, s.N, formFactor, clippedFormFactor);
    float diffuseIrradiance = 0.5 * max(dot(s.N, clippedFormFactor), 0.0);
    float shaping = shapingAttenuation(light, normalize(toPoint));
    vec3 radiance = light.radiance.rgb * shaping;
    vec3 result = diffuseBrdf(s) * clearcoatTransmission(s) * light.factors.x * radiance * diffuseIrradiance;

    // Representative point: where the mirror direction meets the light's plane, clamped to the shape.
    vec3 R = reflect(-s.V, s.N);
    vec3 centre = light.positionType.xyz - s.P;
    float facing = dot(R, axis);
    vec3 hit = facing < -1e-4 ? R * (dot(centre, axis) / facing) : R * 1e4;
    vec3 onPlane = hit - axis * dot(hit - centre, axis) - centre;  // relative to the centre, in the plane
    vec2 local = vec2(dot(onPlane, light.axisX.xyz) / dot(light.axisX.xyz, light.axisX.xyz),
                      dot(onPlane, light.axisY.xyz) / dot(light.axisY.xyz, light.axisY.xyz));
    local = uint(light.positionType.w) == LIGHT_RECT ? clamp(local, -1.0, 1.0) : local / max(1.0, length(local));
    vec3 L = normalize(centre + local.x * light.axisX.xyz + local.y * light.axisY.xyz);
    // Irradiance at normal incidence of the whole source: |vector form factor| / 2 (it is L times
    // the projected solid angle the light subtends when faced head on).
    float solidAngle = 0.5 * length(formFactor);
    float sinHalfAngle = clamp(sqrt(solidAngle / PI), 0.0, 1.0);
    result += specularBrdf(s, L, sinHalfAngle) * light.factors.y * radiance * solidAngle * max(dot(s.N, L), 0.0);
    return result;
}

// --- Cylinder lights ---------------------------------------------------------------------------
// A uniform cylinder (UsdLuxCylinderLight: along local X, emitting from its side, not its caps)
// seen from P is lit as a rectangle as long as it, parallel to its axis and facing P across it,
// with its long edges on the two planes through P tangent to the tube: across the axis it then
// subtends the tube's exact angle, asin(r / d) either side at distance d from the axis, and a long
// tube's irradiance is exact (pi L r / d on a receiver facing it). Along the axis the angle its
// ends subtend depends on how far from P the rectangle lies: at the mean distance of the visible
// half of the side, d - (pi / 4) r (the half circle's depth weighted by its projected width), a
// short tube's ends come out right too, where a rectangle through the axis was 4% dark at
// r / d = 0.16 (CylinderLight tests). The rectangle takes the area lights' exact polygon integral
// and representative point: the light is swapped for it before the lights' common dispatch (no
// arrays, no second call site).
LightData cylinderSeenFrom(LightData light, vec3 P) {
    vec3 along = normalize(light.axisX.xyz);
    vec3 toPoint = P - light.positionType.xyz;
    vec3 across = toPoint - along * dot(toPoint, along);
    float r = light.radiance.a;
    // A point inside the tube is lit as one just outside it.
    float d = max(length(across), r / 0.99);
    // On the axis line (beyond a cap) nothing of the side is seen; any facing gives that.
    vec3 facing = dot(across, across) > 0.0
                      ? normalize(across)
                      : normalize(cross(along, abs(along.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    float depth = d - 0.25 * PI * r;
    LightData rectangle = light;
    rectangle.positionType = vec4(light.positionType.xyz + facing * (0.25 * PI * r), float(LIGHT_RECT));
    rectangle.directionAngle.xyz = facing;
    rectangle.axisY = vec4(cross(facing, along) * (depth * r / sqrt(d * d - r * r)), 0.0);
    return rectangle;
}

// --- All light types ------------------------------------------------------------------------

bool isLocalLight(LightData light) {
    uint type = uint(light.positionType.w);
    return type != LIGHT_DISTANT && type != LIGHT_DOME;
}

// Whether a local light's light reaches P at all: its irradiance bound is above the threshold that
// set its influence range R (delegate/prims/light.cpp: L A / d^2 >= T, R^2 = L A / T), and P lies
// inside its ShapingAPI cone. A rect or disk is a Lambert emitter: a point whose distance from the
// light's plane is z receives at most L A z / (d - s)^3 from it (every emitter point is at least
// d - s away, s the half diagonal, and sees P at the cosine z / its distance), so it reaches no
// farther than (d - s)^3 <= R^2 z: about a third of the sphere's volume. The tests are exact
// against the evaluation (the cone is taken from the light's centre there too), so no pixel's
// light depends on its tile.
bool lightReaches(LightData light, vec3 P) {
    if (!isLocalLight(light)) return true;
    vec3 d = P - light.positionType.xyz;
    float d2 = dot(d, d), range = light.factors.w;
    if (d2 > range * range) return false;
    float distance = sqrt(d2), along = dot(d, light.directionAngle.xyz);
    if (hasLightKind(LIGHT_KINDS, LIGHT_KIND_SHAPED) && light.shaping.x < 0.5 * PI && along < cos(light.shaping.x) * distance)
        return false;
    uint type = uint(light.positionType.w);
    if ((hasLightType(LIGHT_KINDS, LIGHT_RECT) || hasLightType(LIGHT_KINDS, LIGHT_DISK)) &&
        (type == LIGHT_RECT || type == LIGHT_DISK)) {
        if (along <= 0.0) return false;
        float beyond = distance - areaLightHalfDiagonal(light);
        if (beyond > 0.0 && beyond * beyond * beyond > range * range * along) return false;
    }
    return true;
}

// The smallest of the spheres known to hold every point lightReaches accepts (xyz the centre, w the
// radius), for the lighting pass's tiles and depth slices. The influence sphere itself; for a rect
// or disk the sphere around its Lambert lobe (d - s)^3 <= R^2 z: centre R/3 along the axis, radius
// 2R/3 for a point emitter (the lobe's farthest point from there is its tip, on the axis at R), and
// 2R/3 + 2.25 s with the half diagonal s; for a cone of half angle c its
// sector's bounding sphere (centre R / (2 cos c) along the axis and that radius below 45 degrees,
// else centre R cos c, radius R sin c).
vec4 influenceSphere(LightData light) {
    vec3 centre = light.positionType.xyz, axis = light.directionAngle.xyz;
    float range = light.factors.w;
    vec4 sphere = vec4(centre, range);
    uint type = uint(light.positionType.w);
    if (type == LIGHT_RECT || type == LIGHT_DISK) {
        float radius = 2.0 / 3.0 * range + 2.25 * areaLightHalfDiagonal(light);
        if (radius < sphere.w) sphere = vec4(centre + axis * (range / 3.0), radius);
    }
    float cone = light.shaping.x;
    if (cone < 0.5 * PI) {
        vec4 sector = cone > 0.25 * PI ? vec4(centre + axis * (range * cos(cone)), range * sin(cone))
                                       : vec4(centre + axis * (0.5 * range / cos(cone)), 0.5 * range / cos(cone));
        if (sector.w < sphere.w) sphere = sector;
    }
    return sphere;
}

// A distant or sphere light as the point P sees it: the unit direction to it, the irradiance it
// gives at normal incidence and the sine of its angular radius (0: a point).
struct DirectionalSource {
    vec3 L;
    vec3 irradiance;
    float sinHalfAngle;
};

DirectionalSource directionalSource(LightData light, vec3 P, uint kinds) {
    DirectionalSource source;
    if (!hasLightType(kinds, LIGHT_SPHERE) || uint(light.positionType.w) == LIGHT_DISTANT) {
        // UsdLux: irradiance = radiance x solid angle of the disc (precomputed on the host).
        source.L = -light.directionAngle.xyz;
        source.irradiance = light.radiance.rgb;
        source.sinHalfAngle = sin(light.directionAngle.w);
        return source;
    }
    vec3 toLight = light.positionType.xyz - P;
    float d2 = max(dot(toLight, toLight), 1e-8);
    float d = sqrt(d2);
    source.L = toLight / d;
    float r = light.radiance.a;
    // A uniform sphere of radiance L_e and radius r fully above the horizon gives
    // E = pi * L_e * (r/d)^2 * cos(theta); a point light (r folded in) follows the same law.
    source.irradiance = PI * light.radiance.rgb * (r * r) / d2 * shapingAttenuation(light, -source.L);
    // treatAsPoint keeps the power but not the lobe widening of an extended source.
    source.sinHalfAngle = light.factors.z > 0.0 ? 0.0 : clamp(r / d, 0.0, 1.0);
    return source;
}

vec3 reflectFromLight(SurfacePoint s, LightData light, uint kinds) {
    if (hasLightType(kinds, LIGHT_CYLINDER) && uint(light.positionType.w) == LIGHT_CYLINDER)
        light = cylinderSeenFrom(light, s.P);
    uint type = uint(light.positionType.w);
    if ((hasLightType(kinds, LIGHT_DISTANT) || hasLightType(kinds, LIGHT_SPHERE)) &&
        (type == LIGHT_DISTANT || type == LIGHT_SPHERE)) {
        DirectionalSource source = directionalSource(light, s.P, kinds);
        return reflectFromDirection(s, source.L, source.irradiance, source.sinHalfAngle, light.factors.xy);
    }
    if ((hasLightType(kinds, LIGHT_RECT) || hasLightType(kinds, LIGHT_DISK) || hasLightType(kinds, LIGHT_CYLINDER)) &&
        (type == LIGHT_RECT || type == LIGHT_DISK))
        return reflectFromAreaLight(s, light);
    if (!hasLightType(kinds, LIGHT_DOME)) return vec3(0.0);
    // LIGHT_DOME: Lambert integrates to albedo x irradiance / pi (albedo x L for a constant
    // dome); GGX is the split sum (Karis 2013): the prefiltered radiance (L for a constant dome)
    // times the pre-integrated response (environmentBrdf), for the base and the coat.
    bool textured = light.factors.z > 0.5;
    vec3 diffuseRadiance = textured ? s.environment.diffuse : vec3(1.0);
    vec3 specularRadiance = textured ? s.environment.specular : vec3(1.0);
    vec3 coatRadiance = textured ? s.environment.coat : vec3(1.0);
    float NdotV = max(dot(s.N, s.V), 1e-4);
    vec2 base = environmentBrdf(s.roughness, NdotV);
    vec2 coat = environmentBrdf(s.clearcoatRoughness, NdotV);
    float transmission = clearcoatTransmission(s);
    vec3 specular = (s.f0 * base.x + base.y) * transmission * specularRadiance +
                    s.clearcoat * (CLEARCOAT_F0 * coat.x + coat.y) * coatRadiance;
    vec3 diffuse = s.diffuse * transmission * diffuseRadiance;
    return s.ambientAccess * (diffuse * light.factors.x + specular * light.factors.y) * light.radiance.rgb;
}

#endif
