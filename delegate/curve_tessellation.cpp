#include "delegate/curve_tessellation.h"

#include "renderer/matrix.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::delegate {
namespace {

using V3 = Vec3d;

double norm(V3 a) { return length(a); }
// `a` made unit length, or `fallback` where it has none.
V3 normalised(V3 a, V3 fallback) {
    double n = norm(a);
    return n > 1e-20 ? scale(a, 1.0 / n) : fallback;
}
V3 anyPerpendicular(V3 t) { return normalised(cross(t, std::fabs(t[0]) < 0.9 ? V3{1, 0, 0} : V3{0, 1, 0}), {0, 0, 1}); }

constexpr float kGrey = 0.18f;
constexpr double kDefaultWidth = 1.0;  // Hydra's fallback for curves and points without widths

// The four basis functions at t and their derivatives (Foley, van Dam et al. 11.2; Catmull-Rom
// with tension 1/2).
void basisAt(CurveBasis basis, double t, std::array<double, 4>& b, std::array<double, 4>& d) {
    const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
    switch (basis) {
        case CurveBasis::Bezier:
            b = {s * s * s, 3 * t * s * s, 3 * t2 * s, t3};
            d = {-3 * s * s, 3 * s * s - 6 * t * s, 6 * t * s - 3 * t2, 3 * t2};
            break;
        case CurveBasis::Bspline:
            b = {s * s * s / 6, (3 * t3 - 6 * t2 + 4) / 6, (-3 * t3 + 3 * t2 + 3 * t + 1) / 6, t3 / 6};
            d = {-s * s / 2, (9 * t2 - 12 * t) / 6, (-9 * t2 + 6 * t + 3) / 6, t2 / 2};
            break;
        case CurveBasis::CatmullRom:
            b = {(-t3 + 2 * t2 - t) / 2, (3 * t3 - 5 * t2 + 2) / 2, (-3 * t3 + 4 * t2 + t) / 2, (t3 - t2) / 2};
            d = {(-3 * t2 + 4 * t - 1) / 2, (9 * t2 - 10 * t) / 2, (-9 * t2 + 8 * t + 1) / 2, (3 * t2 - 2 * t) / 2};
            break;
        case CurveBasis::Linear:
            b = {s, t, 0, 0};
            d = {-1, 1, 0, 0};
            break;
    }
}

// Where each curve starts in the points and in varying primvars.
struct CurveOffsets {
    std::vector<size_t> point, varying;
    std::vector<int> segments;
};
CurveOffsets offsetsOf(const CurvesInput& c) {
    CurveOffsets o;
    size_t point = 0, varying = 0;
    for (int32_t count : c.curveVertexCounts) {
        int segments = curveSegmentCount(c.basis, c.wrap, count);
        o.point.push_back(point);
        o.varying.push_back(varying);
        o.segments.push_back(segments);
        point += size_t(std::max(count, 0));
        varying += size_t(std::max(segments, 0)) + (c.wrap == CurveWrap::Periodic ? 0 : 1);
    }
    return o;
}

// A primvar of `components` per element evaluated on curve `curve` at (segment, t).
class PrimvarEvaluator {
public:
    PrimvarEvaluator(const CurvesInput& c, const CurveOffsets& o, const MeshPrimvar& pv) : c_(c), o_(o), pv_(pv) {}
    std::array<double, 3> at(size_t curve, int segment, double t) const {
        std::array<double, 3> v{};
        auto accumulate = [&](size_t element, double w) {
            for (size_t k = 0; k < pv_.components && k < 3; ++k) v[k] += w * pv_.values[element * pv_.components + k];
        };
        switch (pv_.interpolation) {
            case OBSCURA_INTERPOLATION_CONSTANT: accumulate(0, 1.0); break;
            case OBSCURA_INTERPOLATION_UNIFORM: accumulate(curve, 1.0); break;
            case OBSCURA_INTERPOLATION_VERTEX: {
                CurveWeights w = curveWeights(c_.basis, c_.wrap, c_.curveVertexCounts[curve], segment, t);
                for (int k = 0; k < w.count; ++k) accumulate(o_.point[curve] + size_t(w.index[size_t(k)]), w.weight[size_t(k)]);
                break;
            }
            default: {  // varying, faceVarying: linear between the segment's ends
                int segments = o_.segments[curve];
                int next = c_.wrap == CurveWrap::Periodic ? (segment + 1) % segments : segment + 1;
                accumulate(o_.varying[curve] + size_t(segment), 1.0 - t);
                accumulate(o_.varying[curve] + size_t(next), t);
            }
        }
        return v;
    }

private:
    const CurvesInput& c_;
    const CurveOffsets& o_;
    const MeshPrimvar& pv_;
};

// One point along a curve where a ring (tube) or a cross-section (ribbon) is placed.
struct Sample {
    V3 position, tangent, normal;  // normal: authored (ribbons) only
    double radius;
    std::array<double, 3> color;
    double opacity;
    double u;
};

V3 pointOf(const std::vector<float>& p, size_t i) { return {p[3 * i], p[3 * i + 1], p[3 * i + 2]}; }

std::string countProblem(const char* name, const MeshPrimvar& pv, size_t expected) {
    size_t elements = pv.values.size() / pv.components;
    if (elements == expected && pv.values.size() % pv.components == 0) return {};
    return std::string(name) + " has " + std::to_string(elements) + " elements but its interpolation needs " +
           std::to_string(expected);
}

std::string widthsProblem(const MeshPrimvar& widths, size_t expected) {
    if (std::string problem = countProblem("widths", widths, expected); !problem.empty()) return problem;
    for (size_t i = 0; i < widths.values.size(); ++i)
        if (!(widths.values[i] >= 0.0f))
            return "widths[" + std::to_string(i) + "] is " + std::to_string(widths.values[i]) + "; widths must not be negative";
    return {};
}

// Drops a primvar of the wrong size, with a warning.
const MeshPrimvar* usable(const std::optional<MeshPrimvar>& pv, size_t expected, const char* name,
                          std::vector<std::string>& warnings) {
    if (!pv) return nullptr;
    if (std::string problem = countProblem(name, *pv, expected); !problem.empty()) {
        warnings.push_back(problem + "; ignored");
        return nullptr;
    }
    return &*pv;
}

passes::Vertex vertexAt(V3 position, V3 normal, V3 tangent, const std::array<double, 3>& color, double opacity,
                        double u, double v) {
    passes::Vertex out{};
    for (int k = 0; k < 3; ++k) {
        out.position[k] = float(position[size_t(k)]);
        out.normal[k] = float(normal[size_t(k)]);
        out.color[k] = float(color[size_t(k)]);
        out.tangent[k] = float(tangent[size_t(k)]);
    }
    out.tangent[3] = 1.0f;
    out.color[3] = std::clamp(float(opacity), 0.0f, 1.0f);
    out.uv[0] = float(u);
    out.uv[1] = float(v);
    return out;
}

// Rotates `v` about the unit axis `axis` by `angle` (Rodrigues).
V3 rotateAbout(V3 v, V3 axis, double angle) {
    double c = std::cos(angle), s = std::sin(angle);
    return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)));
}

// Tube frames: rotation-minimising by double reflection (Wang, Juettler, Zheng, Liu 2008,
// "Computation of rotation minimizing frames"), so a tube does not twist along the curve; a
// periodic curve's mismatch after one turn is spread evenly over it so the seam closes.
std::vector<V3> transportedNormals(const std::vector<Sample>& s, bool periodic) {
    std::vector<V3> r(s.size());
    r[0] = anyPerpendicular(s[0].tangent);
    for (size_t i = 0; i + 1 < s.size(); ++i) {
        V3 v1 = sub(s[i + 1].position, s[i].position);
        double c1 = dot(v1, v1);
        if (c1 < 1e-30) {
            r[i + 1] = r[i];
            continue;
        }
        V3 rL = sub(r[i], scale(v1, 2 * dot(v1, r[i]) / c1));
        V3 tL = sub(s[i].tangent, scale(v1, 2 * dot(v1, s[i].tangent) / c1));
        V3 v2 = sub(s[i + 1].tangent, tL);
        double c2 = dot(v2, v2);
        V3 next = c2 < 1e-30 ? rL : sub(rL, scale(v2, 2 * dot(v2, rL) / c2));
        // Kept exactly perpendicular against rounding.
        r[i + 1] = normalised(sub(next, scale(s[i + 1].tangent, dot(next, s[i + 1].tangent))), anyPerpendicular(s[i + 1].tangent));
    }
    if (periodic && s.size() > 1) {
        // Where the frame would arrive back at the first sample, and the angle to its start.
        const Sample& last = s.back();
        V3 v1 = sub(s[0].position, last.position);
        double c1 = dot(v1, v1);
        V3 back = r.back();
        if (c1 > 1e-30) {
            V3 rL = sub(back, scale(v1, 2 * dot(v1, back) / c1));
            V3 tL = sub(last.tangent, scale(v1, 2 * dot(v1, last.tangent) / c1));
            V3 v2 = sub(s[0].tangent, tL);
            double c2 = dot(v2, v2);
            back = c2 < 1e-30 ? rL : sub(rL, scale(v2, 2 * dot(v2, rL) / c2));
        }
        double angle = std::atan2(dot(cross(back, r[0]), s[0].tangent), dot(back, r[0]));
        for (size_t i = 1; i < s.size(); ++i) r[i] = rotateAbout(r[i], s[i].tangent, angle * double(i) / double(s.size()));
    }
    return r;
}

// Samples along one curve: `steps` per segment (1 for linear curves), plus the end of a nonperiodic one.
std::vector<Sample> samplesOf(const CurvesInput& c, const CurveOffsets& o, size_t curve, int steps,
                              const PrimvarEvaluator* widths, const PrimvarEvaluator* normals,
                              const PrimvarEvaluator* colors, const PrimvarEvaluator* opacities) {
    const int n = c.curveVertexCounts[curve], segments = o.segments[curve];
    const bool periodic = c.wrap == CurveWrap::Periodic;
    if (c.basis == CurveBasis::Linear) steps = 1;
    std::vector<Sample> out;
    const int total = segments * steps + (periodic ? 0 : 1);
    for (int i = 0; i < total; ++i) {
        int segment = std::min(i / steps, segments - 1);
        double t = double(i - segment * steps) / steps;
        CurveWeights w = curveWeights(c.basis, c.wrap, n, segment, t);
        Sample s{};
        for (int k = 0; k < w.count; ++k) {
            V3 p = pointOf(c.points, o.point[curve] + size_t(w.index[size_t(k)]));
            s.position = add(s.position, scale(p, w.weight[size_t(k)]));
            s.tangent = add(s.tangent, scale(p, w.derivative[size_t(k)]));
        }
        // Bezier segments may join at a corner (their shared point's slopes differ): the ring
        // there takes the mean of both directions, as a polyline's does.
        if (c.basis == CurveBasis::Bezier && t == 0.0 && (segment > 0 || periodic)) {
            CurveWeights before = curveWeights(c.basis, c.wrap, n, (segment + segments - 1) % segments, 1.0);
            V3 incoming{0, 0, 0};
            for (int k = 0; k < before.count; ++k)
                incoming = add(incoming, scale(pointOf(c.points, o.point[curve] + size_t(before.index[size_t(k)])),
                                               before.derivative[size_t(k)]));
            s.tangent = add(normalised(incoming, {0, 0, 0}), normalised(s.tangent, {0, 0, 0}));
        }
        s.radius = widths ? std::max(0.0, 0.5 * widths->at(curve, segment, t)[0]) : 0.5 * kDefaultWidth;
        if (normals) s.normal = normals->at(curve, segment, t);
        s.color = colors ? colors->at(curve, segment, t) : std::array<double, 3>{kGrey, kGrey, kGrey};
        s.opacity = opacities ? opacities->at(curve, segment, t)[0] : 1.0;
        s.u = (segment + t) / segments;
        out.push_back(s);
    }
    // Unit tangents; linear joints (and cubic points with a vanishing derivative) take the mean
    // of the chords on either side, so a polyline's tube mitres its corners.
    for (size_t i = 0; i < out.size(); ++i) {
        size_t prev = i > 0 ? i - 1 : (periodic ? out.size() - 1 : i);
        size_t next = i + 1 < out.size() ? i + 1 : (periodic ? 0 : i);
        V3 chords = add(normalised(sub(out[i].position, out[prev].position), {0, 0, 0}),
                        normalised(sub(out[next].position, out[i].position), {0, 0, 0}));
        bool useChords = c.basis == CurveBasis::Linear || norm(out[i].tangent) < 1e-12;
        out[i].tangent = normalised(useChords ? chords : out[i].tangent, normalised(chords, {0, 0, 1}));
    }
    return out;
}

uint32_t tubeIndex(uint32_t base, int sides, size_t ring, int side) { return base + uint32_t(ring * size_t(sides) + size_t(side % sides)); }

void writeTube(MeshGeometry& out, const std::vector<Sample>& samples, int sides, bool periodic) {
    const std::vector<V3> frames = transportedNormals(samples, periodic);
    const uint32_t base = uint32_t(out.vertices.size());
    for (size_t i = 0; i < samples.size(); ++i) {
        const Sample& s = samples[i];
        V3 u = frames[i], v = cross(s.tangent, u);
        for (int k = 0; k < sides; ++k) {
            double phi = 2.0 * std::numbers::pi * k / sides;
            V3 radial = add(scale(u, std::cos(phi)), scale(v, std::sin(phi)));
            out.vertices.push_back(vertexAt(add(s.position, scale(radial, s.radius)), radial, s.tangent, s.color,
                                            s.opacity, s.u, double(k) / sides));
        }
    }
    // Quads (ring i, side k) -> (i, k+1) -> (i+1, k+1) -> (i+1, k): around then along, the
    // cross product of which points outwards, so they wind counter-clockwise seen from outside.
    const size_t rings = samples.size(), bands = periodic ? rings : rings - 1;
    for (size_t i = 0; i < bands; ++i)
        for (int k = 0; k < sides; ++k) {
            size_t j = (i + 1) % rings;
            uint32_t a = tubeIndex(base, sides, i, k), b = tubeIndex(base, sides, i, k + 1);
            uint32_t c = tubeIndex(base, sides, j, k + 1), d = tubeIndex(base, sides, j, k);
            out.indices.insert(out.indices.end(), {a, b, c, a, c, d});
        }
    if (periodic) return;
    // Flat caps facing back along the curve at its start and forwards at its end.
    for (bool end : {false, true}) {
        const Sample& s = end ? samples.back() : samples.front();
        const size_t ring = end ? rings - 1 : 0;
        const uint32_t capBase = uint32_t(out.vertices.size());
        V3 facing = scale(s.tangent, end ? 1.0 : -1.0);
        for (int k = 0; k < sides; ++k) {
            passes::Vertex v = out.vertices[tubeIndex(base, sides, ring, k)];
            for (int j = 0; j < 3; ++j) v.normal[j] = float(facing[size_t(j)]);
            out.vertices.push_back(v);
        }
        // Around the ring is counter-clockwise seen from the end the tangent points to.
        for (int k = 1; k + 1 < sides; ++k) {
            uint32_t a = capBase, b = capBase + uint32_t(k), c = capBase + uint32_t(k + 1);
            if (end) out.indices.insert(out.indices.end(), {a, b, c});
            else out.indices.insert(out.indices.end(), {a, c, b});
        }
    }
}

void writeRibbon(MeshGeometry& out, const std::vector<Sample>& samples, bool periodic) {
    const uint32_t base = uint32_t(out.vertices.size());
    for (const Sample& s : samples) {
        // The authored normal made perpendicular to the curve; the ribbon spans tangent x normal.
        V3 n = normalised(sub(s.normal, scale(s.tangent, dot(s.normal, s.tangent))), anyPerpendicular(s.tangent));
        V3 across = cross(s.tangent, n);
        V3 left = sub(s.position, scale(across, s.radius)), right = add(s.position, scale(across, s.radius));
        for (double side : {1.0, -1.0}) {
            out.vertices.push_back(vertexAt(left, scale(n, side), s.tangent, s.color, s.opacity, s.u, 0.0));
            out.vertices.push_back(vertexAt(right, scale(n, side), s.tangent, s.color, s.opacity, s.u, 1.0));
        }
    }
    // Across x along = normal: (left, right, right', left') winds counter-clockwise seen from the
    // normal's side; the back copy, facing away, winds the other way (a ribbon has two sides).
    const size_t count = samples.size(), intervals = periodic ? count : count - 1;
    for (size_t i = 0; i < intervals; ++i) {
        uint32_t p = base + uint32_t(4 * i), q = base + uint32_t(4 * ((i + 1) % count));
        out.indices.insert(out.indices.end(), {p, p + 1, q + 1, p, q + 1, q});
        out.indices.insert(out.indices.end(), {p + 2, q + 3, p + 3, p + 2, q + 2, q + 3});
    }
}

size_t samplesPerCurve(const CurvesInput& c, int segments, int steps) {
    if (c.basis == CurveBasis::Linear) steps = 1;
    return size_t(segments) * size_t(steps) + (c.wrap == CurveWrap::Periodic ? 0 : 1);
}

}  // namespace

int curveSegmentCount(CurveBasis basis, CurveWrap wrap, int n) {
    const bool periodic = wrap == CurveWrap::Periodic;
    switch (basis) {
        case CurveBasis::Linear: return periodic ? (n >= 3 ? n : -1) : (n >= 2 ? n - 1 : -1);
        case CurveBasis::Bezier:
            // Segments share their end points: 4 + 3 (k - 1) points for k segments, 3 k when closed.
            if (periodic) return n >= 3 && n % 3 == 0 ? n / 3 : -1;
            return n >= 4 && (n - 4) % 3 == 0 ? (n - 4) / 3 + 1 : -1;
        case CurveBasis::Bspline:
        case CurveBasis::CatmullRom:
            if (periodic) return n >= 3 ? n : -1;
            if (wrap == CurveWrap::Pinned) return n >= 2 ? n - 1 : -1;  // with a phantom point at each end
            return n >= 4 ? n - 3 : -1;
    }
    return -1;
}

size_t curvePrimvarElementCount(const CurvesInput& c, ObscuraInterpolation interpolation) {
    switch (interpolation) {
        case OBSCURA_INTERPOLATION_CONSTANT: return 1;
        case OBSCURA_INTERPOLATION_UNIFORM: return c.curveVertexCounts.size();
        case OBSCURA_INTERPOLATION_VARYING:
        case OBSCURA_INTERPOLATION_FACE_VARYING: {
            CurveOffsets o = offsetsOf(c);
            size_t total = 0;
            for (int segments : o.segments) total += size_t(std::max(segments, 0)) + (c.wrap == CurveWrap::Periodic ? 0 : 1);
            return total;
        }
        default: return c.points.size() / 3;
    }
}

std::string curvesProblem(const CurvesInput& c) {
    if (c.curveVertexCounts.empty() && c.points.empty()) return {};  // nothing to draw
    size_t total = 0;
    for (size_t i = 0; i < c.curveVertexCounts.size(); ++i) {
        int32_t n = c.curveVertexCounts[i];
        if (curveSegmentCount(c.basis, c.wrap, n) < 1)
            return "curveVertexCounts[" + std::to_string(i) + "] is " + std::to_string(n) +
                   ", not a vertex count this basis and wrap make segments of";
        total += size_t(n);
    }
    if (total != c.points.size() / 3)
        return "curveVertexCounts sum to " + std::to_string(total) + " but there are " + std::to_string(c.points.size() / 3) +
               " points";
    if (c.widths)
        if (std::string problem = widthsProblem(*c.widths, curvePrimvarElementCount(c, c.widths->interpolation));
            !problem.empty())
            return problem;
    return {};
}

CurveWeights curveWeights(CurveBasis basis, CurveWrap wrap, int n, int segment, double t) {
    std::array<double, 4> b{}, d{};
    basisAt(basis, t, b, d);
    CurveWeights w;
    auto put = [&](int index, double weight, double derivative) {
        for (int k = 0; k < w.count; ++k)
            if (w.index[size_t(k)] == index) {
                w.weight[size_t(k)] += weight;
                w.derivative[size_t(k)] += derivative;
                return;
            }
        w.index[size_t(w.count)] = index;
        w.weight[size_t(w.count)] = weight;
        w.derivative[size_t(w.count)] = derivative;
        ++w.count;
    };
    const bool periodic = wrap == CurveWrap::Periodic;
    const int controls = basis == CurveBasis::Linear ? 2 : 4;
    const int first = basis == CurveBasis::Bezier ? 3 * segment : segment;
    for (int k = 0; k < controls; ++k) {
        int i = first + k;
        if (periodic) put(i % n, b[size_t(k)], d[size_t(k)]);
        else if (wrap == CurveWrap::Pinned && basis != CurveBasis::Linear && basis != CurveBasis::Bezier) {
            // Pinned: points -1 and n are the phantoms 2 P[0] - P[1] and 2 P[n-1] - P[n-2].
            i -= 1;
            if (i < 0) put(0, 2 * b[size_t(k)], 2 * d[size_t(k)]), put(1, -b[size_t(k)], -d[size_t(k)]);
            else if (i >= n) put(n - 1, 2 * b[size_t(k)], 2 * d[size_t(k)]), put(n - 2, -b[size_t(k)], -d[size_t(k)]);
            else put(i, b[size_t(k)], d[size_t(k)]);
        } else put(i, b[size_t(k)], d[size_t(k)]);
    }
    return w;
}

uint64_t curveTriangleCount(const CurvesInput& c, const CurveDetail& detail) {
    const bool periodic = c.wrap == CurveWrap::Periodic, ribbons = c.normals.has_value();
    uint64_t triangles = 0;
    for (int32_t n : c.curveVertexCounts) {
        uint64_t samples = samplesPerCurve(c, curveSegmentCount(c.basis, c.wrap, n), detail.steps);
        uint64_t intervals = periodic ? samples : samples - 1;
        if (ribbons) triangles += 4 * intervals;
        else triangles += 2 * intervals * uint64_t(detail.sides) + (periodic ? 0 : 2 * uint64_t(detail.sides - 2));
    }
    return triangles;
}

double curveBendMagnitude(const CurvesInput& c) {
    if (c.basis == CurveBasis::Linear) return 0.0;
    const CurveOffsets o = offsetsOf(c);
    double widest = 0.0;
    for (size_t curve = 0; curve < c.curveVertexCounts.size(); ++curve)
        for (int segment = 0; segment < o.segments[curve]; ++segment) {
            // The segment's Bezier control points from its ends and end derivatives: Q1 = C(0) +
            // C'(0) / 3, Q2 = C(1) - C'(1) / 3.
            std::array<V3, 2> at{}, slope{};
            for (int end = 0; end < 2; ++end) {
                CurveWeights w = curveWeights(c.basis, c.wrap, c.curveVertexCounts[curve], segment, end);
                for (int k = 0; k < w.count; ++k) {
                    V3 p = pointOf(c.points, o.point[curve] + size_t(w.index[size_t(k)]));
                    at[size_t(end)] = add(at[size_t(end)], scale(p, w.weight[size_t(k)]));
                    slope[size_t(end)] = add(slope[size_t(end)], scale(p, w.derivative[size_t(k)]));
                }
            }
            V3 q0 = at[0], q1 = add(at[0], scale(slope[0], 1.0 / 3)), q2 = sub(at[1], scale(slope[1], 1.0 / 3)), q3 = at[1];
            widest = std::max({widest, norm(add(sub(q0, scale(q1, 2)), q2)), norm(add(sub(q1, scale(q2, 2)), q3))});
        }
    return widest;
}

double curveMaxRadius(const CurvesInput& c) {
    if (!c.widths) return 0.5 * kDefaultWidth;
    double widest = 0.0;
    for (float w : c.widths->values) widest = std::max(widest, 0.5 * double(w));
    return widest;
}

MeshGeometry tessellateCurves(const CurvesInput& c, const CurveDetail& detail) {
    MeshGeometry out;
    const CurveOffsets o = offsetsOf(c);
    const MeshPrimvar* normals = usable(c.normals, curvePrimvarElementCount(c, c.normals ? c.normals->interpolation
                                                                                      : OBSCURA_INTERPOLATION_VERTEX),
                                        "normals", out.warnings);
    auto display = [&](const std::optional<MeshPrimvar>& pv, const char* name) {
        return usable(pv, curvePrimvarElementCount(c, pv ? pv->interpolation : OBSCURA_INTERPOLATION_CONSTANT), name,
                      out.warnings);
    };
    const MeshPrimvar* colors = display(c.displayColor, "primvars:displayColor");
    const MeshPrimvar* opacities = display(c.displayOpacity, "primvars:displayOpacity");
    std::optional<PrimvarEvaluator> widthAt, normalAt, colorAt, opacityAt;
    if (c.widths) widthAt.emplace(c, o, *c.widths);
    if (normals) normalAt.emplace(c, o, *normals);
    if (colors) colorAt.emplace(c, o, *colors);
    if (opacities) opacityAt.emplace(c, o, *opacities);
    const bool periodic = c.wrap == CurveWrap::Periodic;
    for (size_t curve = 0; curve < c.curveVertexCounts.size(); ++curve) {
        std::vector<Sample> samples =
            samplesOf(c, o, curve, detail.steps, widthAt ? &*widthAt : nullptr, normalAt ? &*normalAt : nullptr,
                      colorAt ? &*colorAt : nullptr, opacityAt ? &*opacityAt : nullptr);
        if (normals) writeRibbon(out, samples, periodic);
        else writeTube(out, samples, detail.sides, periodic);
    }
    return out;
}

std::string pointsProblem(const PointsInput& p) {
    if (!p.widths) return {};
    const size_t count = p.points.size() / 3;
    return widthsProblem(*p.widths, p.widths->interpolation == OBSCURA_INTERPOLATION_CONSTANT ? 1 : count);
}

double pointRadius(const PointsInput& p, size_t i) {
    if (!p.widths) return 0.5 * kDefaultWidth;
    return 0.5 * p.widths->values[p.widths->values.size() == 1 ? 0 : i];
}

uint64_t pointTriangleCount(const PointsInput& p) { return uint64_t(p.points.size() / 3) * 12u; }

MeshGeometry pointImpostorBoxes(const PointsInput& p) {
    MeshGeometry out;
    const size_t count = p.points.size() / 3;
    const MeshPrimvar* colors = nullptr;
    if (p.displayColor) {
        size_t expected = p.displayColor->interpolation == OBSCURA_INTERPOLATION_CONSTANT ? 1 : count;
        colors = usable(p.displayColor, expected, "primvars:displayColor", out.warnings);
    }
    const MeshPrimvar* opacities = usable(p.displayOpacity, count, "primvars:displayOpacity", out.warnings);
    // Corner c sits at x = bit 0, y = bit 1, z = bit 2 (0: -, 1: +). Each face as two triangles
    // wound counter-clockwise seen from outside.
    static constexpr std::array<uint32_t, 36> kFaces{0, 2, 3, 0, 3, 1,   // -z
                                                     4, 5, 7, 4, 7, 6,   // +z
                                                     0, 1, 5, 0, 5, 4,   // -y
                                                     2, 6, 7, 2, 7, 3,   // +y
                                                     0, 4, 6, 0, 6, 2,   // -x
                                                     1, 3, 7, 1, 7, 5};  // +x
    out.vertices.reserve(count * 8);
    out.indices.reserve(count * kFaces.size());
    for (size_t i = 0; i < count; ++i) {
        const V3 centre = pointOf(p.points, i);
        const double radius = pointRadius(p, i);
        std::array<double, 3> color{kGrey, kGrey, kGrey};
        if (colors)
            for (size_t k = 0; k < 3; ++k) color[k] = colors->values[(colors->values.size() == 3 ? 0 : i) * 3 + k];
        const uint32_t first = uint32_t(out.vertices.size());
        for (uint32_t c = 0; c < 8; ++c) {
            const V3 corner{c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0};
            const V3 offset = scale(corner, radius);
            passes::Vertex v = vertexAt(add(centre, offset), scale(corner, 1.0 / std::sqrt(3.0)), offset, color,
                                        opacities ? opacities->values[i] : 1.0, 0.5, 0.5);
            v.tangent[3] = float(radius);
            out.vertices.push_back(v);
        }
        for (uint32_t corner : kFaces) out.indices.push_back(first + corner);
    }
    return out;
}

}  // namespace obscura::delegate
