#include "delegate/implicit_tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace obscura::delegate {
namespace {

// A point of a surface of revolution's profile in the shape's own frame (the axis is z): its
// distance from the axis, height and outward normal in the (radial, axial) plane.
struct ProfilePoint {
    double radius, z, normalRadial, normalAxial;
};

// Builds faces with face-varying normals and st into `mesh`; points are written in the frame
// whose z is the shape's axis and mapped onto X, Y or Z at the end (cyclic, so handedness holds).
class PolygonWriter {
public:
    explicit PolygonWriter(MeshInput& mesh) : mesh_(mesh) {
        mesh_.normals = MeshPrimvar{{}, OBSCURA_INTERPOLATION_FACE_VARYING, 3};
        mesh_.st = MeshPrimvar{{}, OBSCURA_INTERPOLATION_FACE_VARYING, 2};
    }
    struct Corner {
        std::array<double, 3> position, normal;
        std::array<double, 2> st;
    };
    // One face, its corners counter-clockwise seen from the side its normals face.
    void face(std::initializer_list<Corner> corners) { face(std::vector<Corner>(corners)); }
    void face(const std::vector<Corner>& corners) {
        mesh_.faceVertexCounts.push_back(int32_t(corners.size()));
        for (const Corner& c : corners) {
            mesh_.faceVertexIndices.push_back(int32_t(mesh_.points.size() / 3));
            for (double p : c.position) mesh_.points.push_back(float(p));
            for (double n : c.normal) mesh_.normals->values.push_back(float(n));
            for (double t : c.st) mesh_.st->values.push_back(float(t));
        }
    }

private:
    MeshInput& mesh_;
};

// Rotates the frame so z becomes `axis` (0 X, 1 Y, 2 Z): (a, b, c) -> X: (c, a, b), Y: (b, c, a).
void alignToAxis(std::vector<float>& xyz, int axis) {
    if (axis == 2) return;
    for (size_t i = 0; i + 2 < xyz.size(); i += 3) {
        float a = xyz[i], b = xyz[i + 1], c = xyz[i + 2];
        if (axis == 0) xyz[i] = c, xyz[i + 1] = a, xyz[i + 2] = b;
        else xyz[i] = b, xyz[i + 1] = c, xyz[i + 2] = a;
    }
}

// Revolves `profile` (bottom to top) about z in `segments` steps; t is the height's fraction of
// [zMin, zMax]. A ring on the axis (a pole, an apex) closes its band with triangles.
void revolve(PolygonWriter& out, const std::vector<ProfilePoint>& profile, int segments, double zMin, double zMax) {
    const double span = zMax - zMin;
    auto corner = [&](const ProfilePoint& p, int step) {
        double phi = 2.0 * std::numbers::pi * step / segments;
        double c = std::cos(phi), s = std::sin(phi);
        return PolygonWriter::Corner{{p.radius * c, p.radius * s, p.z},
                                     {p.normalRadial * c, p.normalRadial * s, p.normalAxial},
                                     {double(step) / segments, span > 0 ? (p.z - zMin) / span : 0.0}};
    };
    for (size_t ring = 0; ring + 1 < profile.size(); ++ring) {
        const ProfilePoint &lower = profile[ring], &upper = profile[ring + 1];
        for (int step = 0; step < segments; ++step) {
            // East x north points outwards: (step, lower), (step + 1, lower), (step + 1, upper), (step, upper).
            if (lower.radius <= 0.0) out.face({corner(lower, step), corner(upper, step + 1), corner(upper, step)});
            else if (upper.radius <= 0.0) out.face({corner(lower, step), corner(lower, step + 1), corner(upper, step)});
            else out.face({corner(lower, step), corner(lower, step + 1), corner(upper, step + 1), corner(upper, step)});
        }
    }
}

// A flat disk cap at height z facing +z (`up`) or -z, its st the square around it.
void cap(PolygonWriter& out, double radius, double z, bool up, int segments) {
    if (radius <= 0.0) return;
    std::vector<PolygonWriter::Corner> corners;
    for (int k = 0; k < segments; ++k) {
        int step = up ? k : segments - k;  // counter-clockwise seen from the side it faces
        double phi = 2.0 * std::numbers::pi * step / segments;
        double c = std::cos(phi), s = std::sin(phi);
        corners.push_back({{radius * c, radius * s, z}, {0, 0, up ? 1.0 : -1.0}, {0.5 + 0.5 * c, 0.5 + 0.5 * s}});
    }
    out.face(corners);
}

// Profile points of a sphere's arc of `radius` centred at height `centre`, from latitude `from`
// to `to` (radians, 0 at the equator), in steps no larger than 2 pi / segments.
void arc(std::vector<ProfilePoint>& profile, double radius, double centre, double from, double to, int segments) {
    int steps = std::max(1, int(std::ceil((to - from) / (2.0 * std::numbers::pi / segments) - 1e-9)));
    for (int k = 0; k <= steps; ++k) {
        double latitude = k == steps ? to : from + (to - from) * k / steps;
        double c = std::cos(latitude), s = std::sin(latitude);
        // The poles sit exactly on the axis, so their band closes with triangles.
        profile.push_back({std::abs(latitude) >= std::numbers::pi / 2 ? 0.0 : radius * c, centre + radius * s, c, s});
    }
}

void cube(PolygonWriter& out, double half) {
    // Each face: its normal axis and sign; u x v = normal keeps the corners counter-clockwise.
    for (int axis = 0; axis < 3; ++axis)
        for (double sign : {1.0, -1.0}) {
            std::array<double, 3> n{}, u{}, v{};
            n[size_t(axis)] = sign;
            u[size_t((axis + 1) % 3)] = 1.0;
            v[size_t((axis + 2) % 3)] = sign;
            auto corner = [&](double s, double t) {
                std::array<double, 3> p{};
                for (size_t j = 0; j < 3; ++j) p[j] = half * (n[j] + (2 * s - 1) * u[j] + (2 * t - 1) * v[j]);
                return PolygonWriter::Corner{p, n, {s, t}};
            };
            out.face({corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)});
        }
}

void plane(MeshInput& mesh, const ImplicitShape& shape) {
    // UsdGeomPlane: width along x (z when the axis is X), length along y (z when the axis is Y).
    std::array<double, 3> n{}, u{}, v{};
    n[size_t(shape.axis)] = 1.0;
    u[shape.axis == 0 ? 2 : 0] = 1.0;
    v[shape.axis == 1 ? 2 : 1] = 1.0;
    const bool flipped = shape.axis != 2;  // u x v = -n (z x y = -x, x x z = -y): wind the other way round
    PolygonWriter out(mesh);
    auto corner = [&](double s, double t) {
        std::array<double, 3> p{};
        for (size_t j = 0; j < 3; ++j) p[j] = (s - 0.5) * shape.width * u[j] + (t - 0.5) * shape.length * v[j];
        return PolygonWriter::Corner{p, n, {s, t}};
    };
    if (flipped) out.face({corner(0, 0), corner(0, 1), corner(1, 1), corner(1, 0)});
    else out.face({corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)});
}

std::string mustBePositive(const char* name, double value) {
    return value > 0.0 ? std::string() : std::string(name) + " is " + std::to_string(value) + "; it must be positive";
}

}  // namespace

std::string implicitShapeProblem(const ImplicitShape& s) {
    std::string problem;
    auto check = [&](const char* name, double value) {
        if (problem.empty()) problem = mustBePositive(name, value);
    };
    switch (s.kind) {
        case ImplicitKind::Cube: check("size", s.size); break;
        case ImplicitKind::Sphere: check("radius", s.radiusBottom); break;
        case ImplicitKind::Plane:
            check("width", s.width);
            check("length", s.length);
            break;
        case ImplicitKind::Frustum:
            check("height", s.height);
            if (problem.empty() && (s.radiusBottom < 0.0 || s.radiusTop < 0.0 || s.radiusBottom + s.radiusTop <= 0.0))
                problem = "radii are " + std::to_string(s.radiusBottom) + " (bottom) and " + std::to_string(s.radiusTop) +
                          " (top); they must not be negative nor both 0";
            break;
        case ImplicitKind::Capsule:
            check("radiusBottom", s.radiusBottom);
            check("radiusTop", s.radiusTop);
            if (problem.empty() && !(s.height >= 0.0)) problem = "height is " + std::to_string(s.height) + "; it must not be negative";
            // The cone joining the caps touches both only when neither sphere holds the other.
            if (problem.empty() && s.radiusBottom != s.radiusTop && !(std::abs(s.radiusBottom - s.radiusTop) < s.height))
                problem = "height " + std::to_string(s.height) + " is not more than the difference of the radii " +
                          std::to_string(s.radiusBottom) + " and " + std::to_string(s.radiusTop);
            break;
    }
    return problem;
}

Aabb implicitShapeBounds(const ImplicitShape& s) {
    Aabb box;
    std::array<double, 3> lo{}, hi{};
    switch (s.kind) {
        case ImplicitKind::Cube: lo = {-s.size / 2, -s.size / 2, -s.size / 2}, hi = {s.size / 2, s.size / 2, s.size / 2}; break;
        case ImplicitKind::Sphere: {
            double r = s.radiusBottom;
            lo = {-r, -r, -r}, hi = {r, r, r};
            break;
        }
        case ImplicitKind::Frustum: {
            double r = std::max(s.radiusBottom, s.radiusTop);
            lo = {-r, -r, -s.height / 2}, hi = {r, r, s.height / 2};
            break;
        }
        case ImplicitKind::Capsule: {
            double r = std::max(s.radiusBottom, s.radiusTop);
            lo = {-r, -r, -s.height / 2 - s.radiusBottom}, hi = {r, r, s.height / 2 + s.radiusTop};
            break;
        }
        case ImplicitKind::Plane: {
            // Its polygon's own bounds, flat along the axis.
            MeshInput mesh;
            plane(mesh, s);
            for (size_t i = 0; i + 2 < mesh.points.size(); i += 3) box.extend({mesh.points[i], mesh.points[i + 1], mesh.points[i + 2]});
            return box;
        }
    }
    // Shapes written about z: their extents along the axis move with it.
    std::vector<float> corners{float(lo[0]), float(lo[1]), float(lo[2]), float(hi[0]), float(hi[1]), float(hi[2])};
    alignToAxis(corners, s.kind == ImplicitKind::Cube || s.kind == ImplicitKind::Sphere ? 2 : s.axis);
    box.extend({corners[0], corners[1], corners[2]});
    box.extend({corners[3], corners[4], corners[5]});
    return box;
}

double implicitCurvatureRadius(const ImplicitShape& s) {
    switch (s.kind) {
        case ImplicitKind::Sphere: return s.radiusBottom;
        case ImplicitKind::Frustum:
        case ImplicitKind::Capsule: return std::max(s.radiusBottom, s.radiusTop);
        default: return 0.0;
    }
}

int implicitSegments(int level) { return 8 << std::clamp(level, kImplicitMinLevel, kImplicitMaxLevel); }

double wantedImplicitLevel(double radiusPixels, double maxErrorPixels) {
    if (!(radiusPixels > 0.0)) return kImplicitMinLevel;
    // R pi^2 / (2 N^2) <= e  <=>  N >= pi sqrt(R / (2 e)); level = log2(N / 8).
    double segments = std::numbers::pi * std::sqrt(radiusPixels / (2.0 * maxErrorPixels));
    return std::log2(segments / 8.0);
}

double wantedStepLevel(double bendPixels, double maxErrorPixels) {
    const double steps = std::sqrt(bendPixels / (8.0 * maxErrorPixels));
    return steps > 1.0 ? std::log2(steps) : 0.0;
}

int chooseImplicitLevel(double wantedLevel, int currentLevel) {
    constexpr double kHysteresis = 0.75;
    if (std::isnan(wantedLevel)) wantedLevel = kImplicitMaxLevel;
    if (currentLevel >= 0 && std::abs(wantedLevel - currentLevel) < kHysteresis) return currentLevel;
    return std::clamp(int(std::lround(std::clamp(wantedLevel, -1.0, double(kImplicitMaxLevel) + 1.0))), kImplicitMinLevel,
                      kImplicitMaxLevel);
}

MeshInput tessellateImplicitShape(const ImplicitShape& s, int segments, bool leftHanded) {
    MeshInput mesh;
    int axis = 2;
    {
        PolygonWriter out(mesh);
        std::vector<ProfilePoint> profile;
        switch (s.kind) {
            case ImplicitKind::Cube: cube(out, s.size / 2); break;
            case ImplicitKind::Plane: plane(mesh, s); break;
            case ImplicitKind::Sphere:
                arc(profile, s.radiusBottom, 0.0, -std::numbers::pi / 2, std::numbers::pi / 2, segments);
                revolve(out, profile, segments, -s.radiusBottom, s.radiusBottom);
                break;
            case ImplicitKind::Frustum: {
                // The side's outward normal is perpendicular to its slope (rTop - rBottom, height).
                axis = s.axis;
                double nr = s.height, nz = s.radiusBottom - s.radiusTop, len = std::hypot(nr, nz);
                profile = {{s.radiusBottom, -s.height / 2, nr / len, nz / len}, {s.radiusTop, s.height / 2, nr / len, nz / len}};
                revolve(out, profile, segments, -s.height / 2, s.height / 2);
                cap(out, s.radiusBottom, -s.height / 2, false, segments);
                cap(out, s.radiusTop, s.height / 2, true, segments);
                break;
            }
            case ImplicitKind::Capsule: {
                // Spheres centred at -height/2 and +height/2 joined by the cone tangent to both:
                // its normal leans by alpha, sin(alpha) = (rBottom - rTop) / height (0: a cylinder).
                axis = s.axis;
                double alpha = s.height > 0.0 ? std::asin((s.radiusBottom - s.radiusTop) / s.height) : 0.0;
                arc(profile, s.radiusBottom, -s.height / 2, -std::numbers::pi / 2, alpha, segments);
                arc(profile, s.radiusTop, s.height / 2, alpha, std::numbers::pi / 2, segments);
                revolve(out, profile, segments, -s.height / 2 - s.radiusBottom, s.height / 2 + s.radiusTop);
                break;
            }
        }
    }
    if (s.kind != ImplicitKind::Plane) {
        alignToAxis(mesh.points, axis);
        alignToAxis(mesh.normals->values, axis);
    }
    if (leftHanded) {
        // Inside out: the winding flips (MeshInput::leftHanded) and so do the normals.
        mesh.leftHanded = true;
        for (float& n : mesh.normals->values) n = -n;
    }
    return mesh;
}

}  // namespace obscura::delegate
