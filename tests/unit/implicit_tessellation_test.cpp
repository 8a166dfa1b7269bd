// Implicit surfaces' polygons against their definitions (UsdGeom): points on the surface, unit
// normals that point outwards, faces wound counter-clockwise about them, and a segment count
// whose chords stay within the error bound the level was chosen for.
#include "delegate/implicit_tessellation.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

namespace obscura::delegate {
namespace {

using V3 = std::array<double, 3>;

V3 at(const std::vector<float>& xyz, size_t i) { return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }
double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }

// Every face's corners wind counter-clockwise about its normals, which are unit vectors.
void expectConsistentFaces(const MeshInput& mesh) {
    ASSERT_TRUE(mesh.normals.has_value());
    size_t base = 0;
    for (int32_t count : mesh.faceVertexCounts) {
        V3 p0 = at(mesh.points, size_t(mesh.faceVertexIndices[base]));
        V3 area{0, 0, 0};
        for (int32_t k = 1; k + 1 < count; ++k) {
            V3 c = cross(sub(at(mesh.points, size_t(mesh.faceVertexIndices[base + size_t(k)])), p0),
                         sub(at(mesh.points, size_t(mesh.faceVertexIndices[base + size_t(k) + 1])), p0));
            for (int j = 0; j < 3; ++j) area[size_t(j)] += c[size_t(j)];
        }
        for (int32_t k = 0; k < count; ++k) {
            V3 n = at(mesh.normals->values, base + size_t(k));
            EXPECT_NEAR(dot(n, n), 1.0, 1e-5);
            EXPECT_GT(dot(n, area), 0.0) << "face at corner " << base;
        }
        base += size_t(count);
    }
}

TEST(ImplicitTessellation, SpherePointsLieOnItAndNormalsPointOut) {
    ImplicitShape s;
    s.kind = ImplicitKind::Sphere;
    s.radiusBottom = 1.5;
    MeshInput mesh = tessellateImplicitShape(s, 32, false);
    expectConsistentFaces(mesh);
    for (size_t i = 0; i < mesh.points.size() / 3; ++i) {
        V3 p = at(mesh.points, i), n = at(mesh.normals->values, i);
        EXPECT_NEAR(std::sqrt(dot(p, p)), 1.5, 1e-5);
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(n[size_t(j)], p[size_t(j)] / 1.5, 1e-5);
    }
}

TEST(ImplicitTessellation, CubeFacesAreFlatAndFaceTheAxes) {
    ImplicitShape s;
    s.kind = ImplicitKind::Cube;
    s.size = 3.0;
    MeshInput mesh = tessellateImplicitShape(s, 8, false);
    ASSERT_EQ(mesh.faceVertexCounts.size(), 6u);
    expectConsistentFaces(mesh);
    int seen[3][2] = {};
    for (size_t i = 0; i < mesh.points.size() / 3; ++i) {
        V3 p = at(mesh.points, i), n = at(mesh.normals->values, i);
        int axis = std::abs(n[0]) > 0.5 ? 0 : std::abs(n[1]) > 0.5 ? 1 : 2;
        EXPECT_NEAR(std::abs(n[size_t(axis)]), 1.0, 1e-6);
        EXPECT_NEAR(p[size_t(axis)], 1.5 * n[size_t(axis)], 1e-6);  // on the face the normal names
        ++seen[axis][n[size_t(axis)] > 0];
    }
    for (auto& axis : seen)
        for (int corners : axis) EXPECT_EQ(corners, 4);
}

TEST(ImplicitTessellation, FrustaConesAndCapsulesAlongEachAxis) {
    for (int axis = 0; axis < 3; ++axis) {
        ImplicitShape cone;
        cone.kind = ImplicitKind::Frustum;
        cone.radiusBottom = 1.0, cone.radiusTop = 0.0, cone.height = 2.0, cone.axis = axis;
        MeshInput mesh = tessellateImplicitShape(cone, 16, false);
        expectConsistentFaces(mesh);
        Aabb bounds = implicitShapeBounds(cone);
        for (size_t i = 0; i < mesh.points.size() / 3; ++i) {
            V3 p = at(mesh.points, i);
            for (size_t j = 0; j < 3; ++j) {
                EXPECT_GE(p[j], bounds.min[j] - 1e-5);
                EXPECT_LE(p[j], bounds.max[j] + 1e-5);
            }
            // UsdGeomCone: the apex at +height/2 along the axis, the base radius at -height/2.
            double along = p[size_t(axis)];
            double across = std::sqrt(dot(p, p) - along * along);
            EXPECT_LE(across, (1.0 - along) / 2.0 + 1e-5);
        }
        ImplicitShape capsule;
        capsule.kind = ImplicitKind::Capsule;
        capsule.radiusBottom = 0.7, capsule.radiusTop = 0.3, capsule.height = 1.0, capsule.axis = axis;
        mesh = tessellateImplicitShape(capsule, 32, false);
        expectConsistentFaces(mesh);
        // Every point on one of the two spheres centred at -+height/2 (the cone between touches both).
        for (size_t i = 0; i < mesh.points.size() / 3; ++i) {
            V3 p = at(mesh.points, i), bottom = p, top = p;
            bottom[size_t(axis)] += 0.5;
            top[size_t(axis)] -= 0.5;
            double onBottom = std::abs(std::sqrt(dot(bottom, bottom)) - 0.7), onTop = std::abs(std::sqrt(dot(top, top)) - 0.3);
            EXPECT_LT(std::min(onBottom, onTop), 1e-5);
        }
    }
}

TEST(ImplicitTessellation, PlaneFacesItsAxisAndSpansWidthAndLength) {
    for (int axis = 0; axis < 3; ++axis) {
        ImplicitShape plane;
        plane.kind = ImplicitKind::Plane;
        plane.width = 4.0, plane.length = 6.0, plane.axis = axis;
        MeshInput mesh = tessellateImplicitShape(plane, 8, false);
        expectConsistentFaces(mesh);
        EXPECT_NEAR(at(mesh.normals->values, 0)[size_t(axis)], 1.0, 1e-6);
        Aabb b = implicitShapeBounds(plane);
        // UsdGeomPlane: width along x (z for axis X), length along y (z for axis Y).
        size_t widthAxis = axis == 0 ? 2 : 0, lengthAxis = axis == 1 ? 2 : 1;
        EXPECT_NEAR(b.max[widthAxis] - b.min[widthAxis], 4.0, 1e-6);
        EXPECT_NEAR(b.max[lengthAxis] - b.min[lengthAxis], 6.0, 1e-6);
        EXPECT_NEAR(b.max[size_t(axis)] - b.min[size_t(axis)], 0.0, 1e-6);
    }
}

// st: a surface of revolution's s is its longitude's fraction of a turn from +x (1 at the seam's
// far side) and t its height's fraction of the shape's; a flat cap's st the square around the
// disc; a cube's faces and a plane each span the unit square, linearly in position.
std::array<double, 2> stAt(const MeshInput& mesh, size_t corner) {
    return {mesh.st->values[2 * corner], mesh.st->values[2 * corner + 1]};
}

void expectRevolvedSt(const MeshInput& mesh, double zMin, double zMax, double capRadius) {
    ASSERT_TRUE(mesh.st.has_value());
    ASSERT_EQ(mesh.st->values.size(), 2 * mesh.points.size() / 3);
    for (size_t i = 0; i < mesh.points.size() / 3; ++i) {
        V3 p = at(mesh.points, i), n = at(mesh.normals->values, i);
        std::array<double, 2> st = stAt(mesh, i);
        if (std::abs(n[2]) > 1.0 - 1e-6 && capRadius > 0.0) {  // a flat cap
            EXPECT_NEAR(st[0], 0.5 + 0.5 * p[0] / capRadius, 1e-5) << "corner " << i;
            EXPECT_NEAR(st[1], 0.5 + 0.5 * p[1] / capRadius, 1e-5) << "corner " << i;
            continue;
        }
        EXPECT_NEAR(st[1], (p[2] - zMin) / (zMax - zMin), 1e-5) << "corner " << i;
        if (std::hypot(p[0], p[1]) < 1e-6) continue;  // a pole: every longitude
        double turn = std::atan2(p[1], p[0]) / (2.0 * std::numbers::pi);
        if (turn < 0.0) turn += 1.0;
        if (st[0] > 0.5 && turn < 1e-6) turn = 1.0;  // the seam, from its far side
        EXPECT_NEAR(st[0], turn, 1e-5) << "corner " << i;
    }
}

TEST(ImplicitTessellation, StFollowsLongitudeAndHeightAndSpansFlatFaces) {
    ImplicitShape sphere;
    sphere.kind = ImplicitKind::Sphere;
    sphere.radiusBottom = 1.5;
    expectRevolvedSt(tessellateImplicitShape(sphere, 16, false), -1.5, 1.5, 0.0);
    ImplicitShape cylinder;
    cylinder.kind = ImplicitKind::Frustum;
    cylinder.height = 3.0;
    expectRevolvedSt(tessellateImplicitShape(cylinder, 16, false), -1.5, 1.5, 1.0);

    ImplicitShape cube;
    cube.kind = ImplicitKind::Cube;
    MeshInput box = tessellateImplicitShape(cube, 8, false);
    ASSERT_TRUE(box.st.has_value());
    for (size_t face = 0; face < 6; ++face) {
        std::array<std::array<double, 2>, 4> st;
        std::array<V3, 4> p;
        for (size_t k = 0; k < 4; ++k) st[k] = stAt(box, 4 * face + k), p[k] = at(box.points, 4 * face + k);
        // The unit square's corners, in order round the face, and st linear in position.
        const std::array<std::array<double, 2>, 4> square{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
        EXPECT_EQ(st, square) << "face " << face;
        V3 across = sub(sub(p[2], p[1]), sub(p[3], p[0]));
        EXPECT_NEAR(dot(across, across), 0.0, 1e-10) << "face " << face;
    }

    ImplicitShape plane;
    plane.kind = ImplicitKind::Plane;
    plane.width = 4.0, plane.length = 6.0;
    MeshInput quad = tessellateImplicitShape(plane, 8, false);
    ASSERT_TRUE(quad.st.has_value());
    for (size_t i = 0; i < quad.points.size() / 3; ++i) {
        V3 p = at(quad.points, i);
        EXPECT_NEAR(stAt(quad, i)[0], p[0] / 4.0 + 0.5, 1e-6);
        EXPECT_NEAR(stAt(quad, i)[1], p[1] / 6.0 + 0.5, 1e-6);
    }
}

TEST(ImplicitTessellation, LeftHandedTurnsTheSurfaceInsideOut) {
    ImplicitShape s;
    s.kind = ImplicitKind::Sphere;
    MeshInput mesh = tessellateImplicitShape(s, 16, true);
    EXPECT_TRUE(mesh.leftHanded);
    for (size_t i = 0; i < mesh.points.size() / 3; ++i) EXPECT_LT(dot(at(mesh.points, i), at(mesh.normals->values, i)), 0.0);
}

TEST(ImplicitTessellation, ChosenSegmentsKeepChordsWithinTheErrorBound) {
    // Rounding the level to the nearest integer changes the count by at most sqrt(2), so the
    // sagitta R (1 - cos(pi / N)) stays within twice the bound wherever the levels are not clamped.
    const double bound = 0.25;
    for (double radius : {20.0, 50.0, 200.0, 1000.0, 4000.0}) {
        int level = chooseImplicitLevel(wantedImplicitLevel(radius, bound), -1);
        double sagitta = radius * (1.0 - std::cos(std::numbers::pi / implicitSegments(level)));
        EXPECT_LE(sagitta, 2.0 * bound) << radius << " px at level " << level;
    }
    // Larger on screen, never fewer segments.
    int last = 0;
    for (double radius = 1.0; radius < 20000.0; radius *= 1.3) {
        int level = chooseImplicitLevel(wantedImplicitLevel(radius, bound), -1);
        EXPECT_GE(level, last);
        last = level;
    }
    EXPECT_EQ(last, kImplicitMaxLevel);
}

TEST(ImplicitTessellation, LevelsHoldWithinTheHysteresisBand) {
    EXPECT_EQ(chooseImplicitLevel(2.7, 2), 2);
    EXPECT_EQ(chooseImplicitLevel(2.3, 3), 3);
    EXPECT_EQ(chooseImplicitLevel(2.8, 2), 3);
    EXPECT_EQ(chooseImplicitLevel(2.2, 3), 2);
    EXPECT_EQ(chooseImplicitLevel(2.6, -1), 3);  // no level yet: the nearest
}

TEST(ImplicitTessellation, BadParametersAreNamed) {
    ImplicitShape sphere;
    sphere.kind = ImplicitKind::Sphere;
    sphere.radiusBottom = -1.0;
    EXPECT_NE(implicitShapeProblem(sphere).find("radius"), std::string::npos);
    ImplicitShape cube;
    cube.kind = ImplicitKind::Cube;
    cube.size = 0.0;
    EXPECT_NE(implicitShapeProblem(cube).find("size"), std::string::npos);
    ImplicitShape capsule;
    capsule.kind = ImplicitKind::Capsule;
    capsule.radiusBottom = 2.0, capsule.radiusTop = 0.5, capsule.height = 1.0;  // one sphere holds the other
    EXPECT_NE(implicitShapeProblem(capsule).find("height"), std::string::npos);
    capsule.height = 2.0;
    EXPECT_EQ(implicitShapeProblem(capsule), "");
}

}  // namespace
}  // namespace obscura::delegate
