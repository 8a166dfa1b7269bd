// Sphere impostors (passes::Draw::sphereImpostors): UsdGeomPoints drawn as exact spheres. The
// delegate draws each point as the cube that bounds its sphere (delegate/curve_tessellation.h
// pointImpostorBoxes); each corner carries, where a mesh carries its tangent, its offset from the
// point and the sphere's radius. The vertex stage turns the offset to world space like a tangent,
// so it interpolates to the offset from the centre of every point of the cube. The fragment stage
// intersects the line through its pixel with the sphere (an ellipsoid under a non-uniform scale:
// intersected in object space), discards misses, and writes the hit's depth and normal: exact
// silhouettes, depth and normals at any size on screen, for 12 triangles a point.
#ifndef OBSCURA_SPHERE_IMPOSTOR_GLSL
#define OBSCURA_SPHERE_IMPOSTOR_GLSL

// The direction of the line of world points that `viewProjection` projects where it projects
// `world`, towards growing depth: the line where the planes clip.x = ndc.x clip.w and
// clip.y = ndc.y clip.w meet, for perspective and orthographic views alike (and a jittered
// projection, which shifts every point of a line alike).
vec3 viewRayDirection(mat4 viewProjection, vec3 world) {
    vec4 clip = viewProjection * vec4(world, 1.0);
    vec2 ndc = clip.xy / clip.w;
    mat4 rows = transpose(viewProjection);
    vec3 dir = cross(rows[0].xyz - ndc.x * rows[3].xyz, rows[1].xyz - ndc.y * rows[3].xyz);
    // d(z/w)/dt along dir has the sign of z' w - z w'.
    float grows = dot(rows[2].xyz, dir) * clip.w - clip.z * dot(rows[3].xyz, dir);
    return normalize(grows < 0.0 ? -dir : dir);
}

// Where the object-space line o + t d meets the sphere of `radius` about the origin: its entry and
// exit parameters, or the closest approach twice where it misses (false).
bool sphereRoots(vec3 o, vec3 d, float radius, out vec2 t) {
    float a = dot(d, d), b = dot(o, d), c = dot(o, o) - radius * radius;
    float disc = b * b - a * c;
    float root = sqrt(max(disc, 0.0));
    t = vec2(-b - root, -b + root) / a;
    return disc >= 0.0;
}

// Whether the line o + t d leaves the cube |x|, |y|, |z| <= radius at o, a point of the cube's
// surface: the face o lies on (its largest coordinate) faces along d.
bool leavesCube(vec3 o, vec3 d) {
    vec3 a = abs(o);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    return o[axis] * d[axis] > 0.0;
}

// Where the line o + t d enters that cube.
float cubeEntry(vec3 o, vec3 d, float radius) {
    float t = -3.4e38;
    for (int i = 0; i < 3; ++i)
        if (d[i] != 0.0) t = max(t, (-sign(d[i]) * radius - o[i]) / d[i]);
    return t;
}

struct ImpostorHit {
    bool hit;         // the line meets the sphere and this fragment answers for it
    vec3 position;    // world
    vec3 normal;      // world, unit, outward
    float depth;      // device depth of `position`; of the closest approach where it misses
    bool backFacing;  // the eye sees the inside (it is within the sphere): the far side
};

// The sphere along the line of sight through `onBox`, a world point of a cube fragment whose
// interpolated corner data is `sphere` (world offset from the centre, object-space radius), seen
// through `viewProjection`; `normalMatrix` the instance's (the inverse transpose of its linear
// part: its transpose takes world directions to object space). The cube is drawn without culling,
// so a pixel may see it twice: the near face answers, and the far face only where the near one is
// clipped by the near plane (the eye inside the cube).
ImpostorHit impostorHit(mat4 viewProjection, mat4 normalMatrix, vec3 onBox, vec4 sphere) {
    mat3 toObject = transpose(mat3(normalMatrix));
    vec3 dir = viewRayDirection(viewProjection, onBox);
    vec3 o = toObject * sphere.xyz, d = toObject * dir;
    ImpostorHit h;
    vec2 t;
    h.hit = sphereRoots(o, d, sphere.w, t);
    if (leavesCube(o, d)) {
        vec4 entry = viewProjection * vec4(onBox + cubeEntry(o, d, sphere.w) * dir, 1.0);
        if (entry.z >= 0.0) h.hit = false;  // the near face is drawn: it answers
    }
    // The near side, unless it lies before the near plane (depth below 0): then the far side.
    vec4 clip = viewProjection * vec4(onBox + t.x * dir, 1.0);
    h.backFacing = clip.z < 0.0;
    float root = h.backFacing ? t.y : t.x;
    if (h.backFacing) clip = viewProjection * vec4(onBox + root * dir, 1.0);
    h.hit = h.hit && clip.z >= 0.0;
    h.position = onBox + root * dir;
    h.normal = normalize(mat3(normalMatrix) * (o + root * d));
    h.depth = clip.z / clip.w;
    return h;
}

// The larger screen slope of device depth (per pixel in x or y) of the sphere's tangent plane at
// `hit`, seen through `viewProjection` from the fragment whose cube point is `onBox`, its screen
// derivatives `dx`, `dy` (on the cube's plane, so exact): the rasteriser's m for a polygon lying
// in that plane, for a depth bias the shader adds itself.
float tangentPlaneDepthSlope(mat4 viewProjection, ImpostorHit hit, vec3 onBox, vec3 dx, vec3 dy) {
    vec3 dir = viewRayDirection(viewProjection, onBox);
    float facing = max(abs(dot(hit.normal, dir)), 1e-4);  // at the rim the plane is seen edge-on
    vec2 slope;
    for (int axis = 0; axis < 2; ++axis) {
        vec3 neighbour = onBox + (axis == 0 ? dx : dy);
        vec3 onPlane = neighbour + dot(hit.normal, hit.position - neighbour) / facing * sign(dot(hit.normal, dir)) * dir;
        vec4 clip = viewProjection * vec4(onPlane, 1.0);
        slope[axis] = abs(clip.z / clip.w - hit.depth);
    }
    return max(slope.x, slope.y);
}

// A tangent frame on the sphere for normal maps and anisotropy: along its parallels about the
// object's z axis (longitude), as a tessellated sphere's u runs.
vec4 impostorTangent(mat4 model, vec3 normal) {
    vec3 objectNormal = transpose(mat3(model)) * normal;  // direction only: the tangent is made unit below
    vec3 east = cross(vec3(0.0, 0.0, 1.0), objectNormal);
    if (dot(east, east) < 1e-12) east = vec3(1.0, 0.0, 0.0);  // at a pole
    return vec4(normalize(mat3(model) * east), 1.0);
}

#endif
