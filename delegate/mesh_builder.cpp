#include "delegate/mesh_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

namespace obscura::delegate {
namespace {

using V3 = std::array<float, 3>;

V3 point(const std::vector<float>& p, size_t i) { return {p[3 * i], p[3 * i + 1], p[3 * i + 2]}; }
V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }

// Index into a primvar's elements for one face-vertex.
size_t primvarIndex(ObscuraInterpolation interpolation, size_t face, size_t faceVertex, size_t pointIndex) {
    switch (interpolation) {
        case OBSCURA_INTERPOLATION_CONSTANT: return 0;
        case OBSCURA_INTERPOLATION_UNIFORM: return face;
        case OBSCURA_INTERPOLATION_FACE_VARYING: return faceVertex;
        default: return pointIndex;
    }
}

float dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The vertex's tangent: `sum` made orthogonal to its normal (Gram-Schmidt), w the sign that turns
// cross(N, T) into the direction of increasing v. Without texture coordinates (or where they do
// not vary) any direction perpendicular to the normal serves.
void setTangent(passes::Vertex& v, const V3* sum, const V3* bitangent) {
    V3 n{v.normal[0], v.normal[1], v.normal[2]};
    V3 t = sum ? *sum : V3{0, 0, 0};
    float along = dot(t, n);
    for (int j = 0; j < 3; ++j) t[j] -= along * n[j];
    float len = std::sqrt(dot(t, t));
    if (!(len > 1e-12f)) {
        t = std::fabs(n[0]) < 0.9f ? cross(n, V3{1, 0, 0}) : cross(n, V3{0, 1, 0});
        len = std::sqrt(dot(t, t));
    }
    for (int j = 0; j < 3; ++j) v.tangent[j] = t[j] / len;
    v.tangent[3] = bitangent && dot(cross(n, t), *bitangent) < 0.0f ? -1.0f : 1.0f;
}

}  // namespace

size_t primvarElementCount(const MeshInput& mesh, ObscuraInterpolation interpolation) {
    switch (interpolation) {
        case OBSCURA_INTERPOLATION_CONSTANT: return 1;
        case OBSCURA_INTERPOLATION_UNIFORM: return mesh.faceVertexCounts.size();
        case OBSCURA_INTERPOLATION_FACE_VARYING: return mesh.faceVertexIndices.size();
        default: return mesh.points.size() / 3;
    }
}

std::string primvarCountProblem(const MeshInput& mesh, const std::optional<MeshPrimvar>& primvar, const char* name) {
    if (!primvar) return {};
    const size_t expected = primvarElementCount(mesh, primvar->interpolation);
    if (primvar->values.size() == expected * primvar->components) return {};
    return std::string(name) + " has " + std::to_string(primvar->values.size() / primvar->components) +
           " elements but its interpolation needs " + std::to_string(expected) + "; ignored";
}

namespace {

// A primvar refinement interpolates, with the name its problems report.
struct InterpolatedPrimvar {
    std::optional<MeshPrimvar> MeshInput::*field;
    const char* name;
};
constexpr InterpolatedPrimvar kDisplayColor{&MeshInput::displayColor, "primvars:displayColor"};
constexpr InterpolatedPrimvar kDisplayOpacity{&MeshInput::displayOpacity, "primvars:displayOpacity"};
constexpr InterpolatedPrimvar kSt{&MeshInput::st, "primvars:st"};

}  // namespace

std::vector<std::string> interpolatedPrimvarProblems(const MeshInput& mesh) {
    std::vector<std::string> problems;
    for (const InterpolatedPrimvar& p : {kDisplayColor, kDisplayOpacity, kSt})
        if (std::string problem = primvarCountProblem(mesh, mesh.*p.field, p.name); !problem.empty())
            problems.push_back(std::move(problem));
    return problems;
}

std::variant<MeshGeometry, std::string> buildMeshGeometry(const MeshInput& mesh) {
    MeshGeometry out;
    const size_t pointCount = mesh.points.size() / 3;
    size_t total = 0;
    for (size_t f = 0; f < mesh.faceVertexCounts.size(); ++f) {
        int32_t c = mesh.faceVertexCounts[f];
        if (c < 3) return "faceVertexCounts[" + std::to_string(f) + "] is " + std::to_string(c) + " (a face needs 3 or more)";
        total += size_t(c);
    }
    if (total != mesh.faceVertexIndices.size())
        return "faceVertexCounts sum to " + std::to_string(total) + " but faceVertexIndices has " +
               std::to_string(mesh.faceVertexIndices.size()) + " entries";
    for (size_t i = 0; i < mesh.faceVertexIndices.size(); ++i) {
        int32_t idx = mesh.faceVertexIndices[i];
        if (idx < 0 || size_t(idx) >= pointCount)
            return "faceVertexIndices[" + std::to_string(i) + "] = " + std::to_string(idx) + " is outside the " +
                   std::to_string(pointCount) + " points";
    }

    auto usable = [&](const std::optional<MeshPrimvar>& pv, const char* name) -> const MeshPrimvar* {
        if (!pv) return nullptr;
        if (std::string problem = primvarCountProblem(mesh, pv, name); !problem.empty()) {
            out.warnings.push_back(std::move(problem));
            return nullptr;
        }
        return &*pv;
    };
    const MeshPrimvar* normals = usable(mesh.normals, "normals");
    const MeshPrimvar* colors = usable(mesh.*kDisplayColor.field, kDisplayColor.name);
    const MeshPrimvar* opacities = usable(mesh.*kDisplayOpacity.field, kDisplayOpacity.name);
    const MeshPrimvar* st = usable(mesh.*kSt.field, kSt.name);

    // Smooth vertex normals when none are authored: area-weighted sum of face normals (the
    // cross products of a fan are twice the triangle areas).
    std::vector<float> smooth;
    if (!normals) {
        smooth.assign(pointCount * 3, 0.0f);
        size_t base = 0;
        for (int32_t count : mesh.faceVertexCounts) {
            V3 p0 = point(mesh.points, size_t(mesh.faceVertexIndices[base]));
            V3 n{0, 0, 0};
            for (int32_t k = 1; k + 1 < count; ++k) {
                V3 e1 = sub(point(mesh.points, size_t(mesh.faceVertexIndices[base + size_t(k)])), p0);
                V3 e2 = sub(point(mesh.points, size_t(mesh.faceVertexIndices[base + size_t(k) + 1])), p0);
                V3 c = cross(e1, e2);
                for (int j = 0; j < 3; ++j) n[j] += c[j];
            }
            if (mesh.leftHanded)
                for (auto& v : n) v = -v;
            for (int32_t k = 0; k < count; ++k) {
                size_t pi = size_t(mesh.faceVertexIndices[base + size_t(k)]);
                for (int j = 0; j < 3; ++j) smooth[3 * pi + size_t(j)] += n[j];
            }
            base += size_t(count);
        }
    }

    // Tangents for tangent-space normal maps (Lengyel 2001, "Computing tangent space basis
    // vectors"): each fan triangle's directions of increasing u and v, summed over the faces that
    // share a point (area-weighted by construction); made orthogonal to each vertex's normal below.
    // XXX: points on a texture seam (faceVarying st) average both sides' directions; MikkTSpace
    // would split them.
    std::vector<V3> tangentSum, bitangentSum;
    if (st) {
        tangentSum.assign(pointCount, V3{0, 0, 0});
        bitangentSum.assign(pointCount, V3{0, 0, 0});
        size_t faceBase = 0;
        for (size_t f = 0; f < mesh.faceVertexCounts.size(); ++f) {
            size_t count = size_t(mesh.faceVertexCounts[f]);
            auto corner = [&](size_t k) {
                size_t fv = faceBase + k, pi = size_t(mesh.faceVertexIndices[fv]);
                const float* uv = &st->values[2 * primvarIndex(st->interpolation, f, fv, pi)];
                return std::make_pair(pi, std::array<float, 2>{uv[0], uv[1]});
            };
            for (size_t k = 1; k + 1 < count; ++k) {
                auto [i0, uv0] = corner(0);
                auto [i1, uv1] = corner(k);
                auto [i2, uv2] = corner(k + 1);
                V3 e1 = sub(point(mesh.points, i1), point(mesh.points, i0));
                V3 e2 = sub(point(mesh.points, i2), point(mesh.points, i0));
                float du1 = uv1[0] - uv0[0], dv1 = uv1[1] - uv0[1], du2 = uv2[0] - uv0[0], dv2 = uv2[1] - uv0[1];
                float det = du1 * dv2 - du2 * dv1;
                if (std::fabs(det) < 1e-20f) continue;
                V3 t, b;
                for (int j = 0; j < 3; ++j) {
                    t[j] = (e1[j] * dv2 - e2[j] * dv1) / det;
                    b[j] = (e2[j] * du1 - e1[j] * du2) / det;
                }
                for (size_t i : {i0, i1, i2})
                    for (int j = 0; j < 3; ++j) tangentSum[i][j] += t[j], bitangentSum[i][j] += b[j];
            }
            faceBase += count;
        }
    }

    // Triangles are written group after group; a face's vertices stay in face order, so the
    // vertex buffer (and a subdivided mesh's shared edges) does not depend on the groups.
    const bool grouped = mesh.faceGroups.size() == mesh.faceVertexCounts.size();
    const uint32_t groupCount = grouped && !mesh.faceGroups.empty()
                                    ? *std::max_element(mesh.faceGroups.begin(), mesh.faceGroups.end()) + 1
                                    : 1;
    std::vector<std::vector<uint32_t>> groupIndices(groupCount);

    // Each face-vertex makes its vertex (face-varying and uniform primvars stay exact); those that
    // make the same vertex, byte for byte, are drawn as one: stored once and shaded once, as the
    // GPU's vertex reuse needs (a smooth mesh's points are shared by four faces or more). Only
    // vertices of one point can be equal, so each point chains the vertices made from it. Which
    // face-vertices meet depends on the primvars' values alone, never on the points: a deforming
    // mesh's shutter positions (drawnPositions) follow the same vertices.
    constexpr uint32_t kNone = UINT32_MAX;
    std::vector<uint32_t> firstOfPoint(pointCount, kNone), nextOfPoint;
    std::vector<uint32_t> corners;
    out.vertices.reserve(pointCount);
    size_t base = 0;
    for (size_t f = 0; f < mesh.faceVertexCounts.size(); ++f) {
        std::vector<uint32_t>& triangles = groupIndices[grouped ? mesh.faceGroups[f] : 0];
        size_t count = size_t(mesh.faceVertexCounts[f]);
        corners.clear();
        for (size_t k = 0; k < count; ++k) {
            size_t fv = base + k;
            size_t pi = size_t(mesh.faceVertexIndices[fv]);
            passes::Vertex v{};
            for (int j = 0; j < 3; ++j) v.position[j] = mesh.points[3 * pi + size_t(j)];
            const float* n = normals ? &normals->values[3 * primvarIndex(normals->interpolation, f, fv, pi)] : &smooth[3 * pi];
            float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int j = 0; j < 3; ++j) v.normal[j] = len > 0 ? n[j] / len : (j == 2 ? 1.0f : 0.0f);
            const float kGrey = 0.18f;
            for (int j = 0; j < 3; ++j)
                v.color[j] = colors ? colors->values[3 * primvarIndex(colors->interpolation, f, fv, pi) + size_t(j)] : kGrey;
            v.color[3] = opacities ? std::clamp(opacities->values[primvarIndex(opacities->interpolation, f, fv, pi)], 0.0f, 1.0f)
                                   : 1.0f;
            for (int j = 0; j < 2 && st; ++j) v.uv[j] = st->values[2 * primvarIndex(st->interpolation, f, fv, pi) + size_t(j)];
            setTangent(v, st ? &tangentSum[pi] : nullptr, st ? &bitangentSum[pi] : nullptr);
            uint32_t index = firstOfPoint[pi];
            while (index != kNone && std::memcmp(&out.vertices[index], &v, sizeof(v)) != 0) index = nextOfPoint[index];
            if (index == kNone) {
                index = uint32_t(out.vertices.size());
                out.vertices.push_back(v);
                nextOfPoint.push_back(firstOfPoint[pi]);
                firstOfPoint[pi] = index;
            }
            corners.push_back(index);
        }
        // Fan triangulation; left-handed meshes wind the other way.
        for (size_t k = 1; k + 1 < count; ++k) {
            uint32_t a = corners[0], b = corners[k], c = corners[k + 1];
            if (mesh.leftHanded) std::swap(b, c);
            triangles.insert(triangles.end(), {a, b, c});
        }
        base += count;
    }
    for (const std::vector<uint32_t>& triangles : groupIndices) {
        out.groupRanges.push_back({uint32_t(out.indices.size()), uint32_t(triangles.size())});
        out.indices.insert(out.indices.end(), triangles.begin(), triangles.end());
    }
    return out;
}

std::vector<float> positionsOf(const MeshGeometry& geometry) {
    std::vector<float> positions;
    positions.reserve(geometry.vertices.size() * 3);
    for (const passes::Vertex& v : geometry.vertices) positions.insert(positions.end(), v.position, v.position + 3);
    return positions;
}

}  // namespace obscura::delegate
