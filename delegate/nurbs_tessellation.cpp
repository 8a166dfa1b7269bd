#include "delegate/nurbs_tessellation.h"

#include <algorithm>
#include <cmath>

namespace obscura::delegate {
namespace {

using Vec3 = std::array<double, 3>;
using V4 = std::array<double, 4>;

Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

using Functions = std::array<double, kMaxNurbsOrder>;

// The order non-zero basis functions N_{first + k} (k = 0..degree) of one direction at t within
// knot span `span` (knots[span] <= t <= knots[span + 1]), and their first and second derivatives.
struct SpanBasis {
    int first = 0;
    Functions value{}, derivative{}, second{};
};

double ratio(double num, double den) { return den > 0.0 ? num / den : 0.0; }  // 0/0 of coincident knots: 0

// d/dt of the degree-`degree` functions of `span` from (the derivatives of) the degree - 1 ones
// (The NURBS Book, eq. 2.7; linear in them, so applied to first derivatives it gives second ones).
Functions derivativeOf(const Functions& lower, int degree, int span, const std::vector<double>& U) {
    Functions out{};
    for (int k = 0; degree >= 1 && k <= degree; ++k) {
        const int i = span - degree + k;
        if (k >= 1) out[size_t(k)] += ratio(degree * lower[size_t(k - 1)], U[size_t(i + degree)] - U[size_t(i)]);
        if (k < degree) out[size_t(k)] -= ratio(degree * lower[size_t(k)], U[size_t(i + degree + 1)] - U[size_t(i + 1)]);
    }
    return out;
}

// Cox-de Boor (The NURBS Book, eq. 2.5), degree by degree.
SpanBasis basisAt(const NurbsDirection& d, int span, double t) {
    const int p = d.order - 1;
    const std::vector<double>& U = d.knots;
    Functions N{}, degreeLess1{}, degreeLess2{};
    N[0] = 1.0;
    for (int degree = 1; degree <= p; ++degree) {
        degreeLess2 = degreeLess1;
        degreeLess1 = N;
        Functions next{};
        for (int k = 0; k <= degree; ++k) {
            const int i = span - degree + k;
            if (k >= 1) next[size_t(k)] += ratio(t - U[size_t(i)], U[size_t(i + degree)] - U[size_t(i)]) * N[size_t(k - 1)];
            if (k < degree)
                next[size_t(k)] += ratio(U[size_t(i + degree + 1)] - t, U[size_t(i + degree + 1)] - U[size_t(i + 1)]) * N[size_t(k)];
        }
        N = next;
    }
    SpanBasis b;
    b.first = span - p;
    b.value = N;
    b.derivative = derivativeOf(degreeLess1, p, span, U);
    if (p >= 2) b.second = derivativeOf(derivativeOf(degreeLess2, p - 1, span, U), p, span, U);
    return b;
}

// A parameter value the grid is evaluated at: its knot span, that span's drawn part [lo, hi].
struct Sample {
    double t;
    int span;
    double lo, hi;
};

// The grid's parameters in one direction: `steps` per drawn span, neighbouring spans sharing
// their boundary sample; `intervalSpan` is the span of each interval between samples.
struct Samples {
    std::vector<Sample> at;
    std::vector<int> intervalSpan;
};

Samples samplesOf(const NurbsDirection& d, int steps) {
    const std::array<double, 2> range = d.drawnRange();
    Samples s;
    for (int span = d.order - 1; span < d.vertexCount; ++span) {
        const double lo = std::max(d.knots[size_t(span)], range[0]), hi = std::min(d.knots[size_t(span + 1)], range[1]);
        if (!(hi > lo)) continue;
        for (int k = s.at.empty() ? 0 : 1; k <= steps; ++k) {
            s.at.push_back({k == steps ? hi : lo + (hi - lo) * k / steps, span, lo, hi});
            if (k > 0) s.intervalSpan.push_back(span);
        }
    }
    return s;
}

using Coefficients = std::array<double, kMaxNurbsOrder * kMaxNurbsOrder>;

// The rational basis R_ab (control point (first u + a, first v + b)) at one (u, v), with its partials.
struct PatchBasis {
    int firstU = 0, firstV = 0, orderU = 0, orderV = 0;
    Coefficients r{}, ru{}, rv{};
};

// R = N_a N_b w / W and its partials (The NURBS Book, eq. 4.8 applied to the basis).
PatchBasis patchBasis(const NurbsPatchInput& patch, const SpanBasis& bu, const SpanBasis& bv) {
    PatchBasis b{bu.first, bv.first, patch.u.order, patch.v.order, {}, {}, {}};
    double W = 0.0, Wu = 0.0, Wv = 0.0;
    for (int j = 0; j < b.orderV; ++j)
        for (int i = 0; i < b.orderU; ++i) {
            const size_t point = size_t(b.firstV + j) * size_t(patch.u.vertexCount) + size_t(b.firstU + i);
            const double w = patch.pointWeights.empty() ? 1.0 : patch.pointWeights[point];
            const size_t k = size_t(j * b.orderU + i);
            b.r[k] = bu.value[size_t(i)] * bv.value[size_t(j)] * w;
            b.ru[k] = bu.derivative[size_t(i)] * bv.value[size_t(j)] * w;
            b.rv[k] = bu.value[size_t(i)] * bv.derivative[size_t(j)] * w;
            W += b.r[k], Wu += b.ru[k], Wv += b.rv[k];
        }
    for (size_t k = 0; k < size_t(b.orderU * b.orderV); ++k) {
        b.r[k] /= W;
        b.ru[k] = (b.ru[k] - b.r[k] * Wu) / W;
        b.rv[k] = (b.rv[k] - b.r[k] * Wv) / W;
    }
    return b;
}

// The sum over the basis of control values (`components` each, u fastest) times `c`, into `out`.
void combine(const PatchBasis& b, const Coefficients& c, const std::vector<float>& values, size_t components,
             int vertexCountU, double* out) {
    std::fill(out, out + components, 0.0);
    for (int j = 0; j < b.orderV; ++j)
        for (int i = 0; i < b.orderU; ++i) {
            const size_t point = size_t(b.firstV + j) * size_t(vertexCountU) + size_t(b.firstU + i);
            const double coefficient = c[size_t(j * b.orderU + i)];
            for (size_t k = 0; k < components; ++k) out[k] += coefficient * values[point * components + k];
        }
}

Vec3 combinePoints(const PatchBasis& b, const Coefficients& c, const NurbsPatchInput& patch) {
    Vec3 sum;
    combine(b, c, patch.points, 3, patch.u.vertexCount, sum.data());
    return sum;
}

// Steps per span at which nurbsBendMagnitude samples the second derivatives in one direction: 8,
// fewer over many spans (at least 2, about 1024 samples a direction), so that a patch of a million
// control points is not evaluated 64 million times. The largest value is at a span's ends for a
// polynomial cubic (linear in between) and at its ends or middle for the conics (symmetric), all
// of which even 2 steps hit.
int bendSamples(const NurbsDirection& d) { return std::clamp(1024 / std::max(d.spanCount(), 1), 2, 8); }

const char* interpolationName(ObscuraInterpolation i) {
    switch (i) {
        case OBSCURA_INTERPOLATION_CONSTANT: return "constant";
        case OBSCURA_INTERPOLATION_UNIFORM: return "uniform";
        case OBSCURA_INTERPOLATION_VARYING: return "varying";
        case OBSCURA_INTERPOLATION_FACE_VARYING: return "faceVarying";
        default: return "vertex";
    }
}

// Elements a primvar of `interpolation` needs on the patch (NurbsPatchInput's counts).
size_t elementCount(const NurbsPatchInput& patch, ObscuraInterpolation interpolation) {
    const size_t spansU = size_t(patch.u.spanCount()), spansV = size_t(patch.v.spanCount());
    switch (interpolation) {
        case OBSCURA_INTERPOLATION_CONSTANT: return 1;
        case OBSCURA_INTERPOLATION_UNIFORM: return spansU * spansV;
        case OBSCURA_INTERPOLATION_VARYING:
        case OBSCURA_INTERPOLATION_FACE_VARYING: return (spansU + 1) * (spansV + 1);
        default: return size_t(patch.u.vertexCount) * size_t(patch.v.vertexCount);
    }
}

class GridWriter {
public:
    GridWriter(const NurbsPatchInput& patch, std::array<int, 2> steps)
        : patch_(patch), us_(samplesOf(patch.u, steps[0])), vs_(samplesOf(patch.v, steps[1])) {}

    NurbsTessellation write() {
        NurbsTessellation out;
        MeshInput& mesh = out.mesh;
        mesh.leftHanded = patch_.leftHanded;
        mesh.normals = MeshPrimvar{{}, OBSCURA_INTERPOLATION_VERTEX, 3};
        auto color = checked(patch_.displayColor, "primvars:displayColor", out.warnings);
        auto opacity = checked(patch_.displayOpacity, "primvars:displayOpacity", out.warnings);
        auto st = checked(patch_.st, "primvars:st", out.warnings);
        if (color) mesh.displayColor = startOutput(*color);
        if (opacity) mesh.displayOpacity = startOutput(*opacity);
        mesh.st = st ? startOutput(*st) : MeshPrimvar{{}, OBSCURA_INTERPOLATION_VERTEX, 2};
        const std::array<double, 2> rangeU = patch_.u.drawnRange(), rangeV = patch_.v.drawnRange();
        for (const Sample& v : vs_.at)
            for (const Sample& u : us_.at) {
                const PatchBasis b = patchBasis(patch_, basisAt(patch_.u, u.span, u.t), basisAt(patch_.v, v.span, v.t));
                for (double x : combinePoints(b, b.r, patch_)) mesh.points.push_back(float(x));
                for (double n : normalAt(b, u, v)) mesh.normals->values.push_back(float(n));
                if (st) appendVertex(*mesh.st, *st, b, u, v);
                else
                    mesh.st->values.insert(mesh.st->values.end(), {float((u.t - rangeU[0]) / (rangeU[1] - rangeU[0])),
                                                                   float((v.t - rangeV[0]) / (rangeV[1] - rangeV[0]))});
                if (color) appendVertex(*mesh.displayColor, *color, b, u, v);
                if (opacity) appendVertex(*mesh.displayOpacity, *opacity, b, u, v);
            }
        const int32_t row = int32_t(us_.at.size());
        for (size_t j = 0; j < vs_.intervalSpan.size(); ++j)
            for (size_t i = 0; i < us_.intervalSpan.size(); ++i) {
                // Counter-clockwise in (u, v): (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1).
                const int32_t corner = int32_t(j) * row + int32_t(i);
                mesh.faceVertexCounts.push_back(4);
                mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(), {corner, corner + 1, corner + row + 1, corner + row});
                for (auto [input, output] : {std::pair{&color, &mesh.displayColor}, std::pair{&opacity, &mesh.displayOpacity},
                                             std::pair{&st, &mesh.st}})
                    if (*input && (*input)->interpolation == OBSCURA_INTERPOLATION_UNIFORM) appendFace(**output, **input, i, j);
            }
        return out;
    }

private:
    // The primvar when its count fits its interpolation, else nullopt and a warning.
    std::optional<MeshPrimvar> checked(const std::optional<MeshPrimvar>& primvar, const char* name,
                                       std::vector<std::string>& warnings) const {
        if (!primvar) return std::nullopt;
        const size_t expected = elementCount(patch_, primvar->interpolation) * primvar->components;
        if (primvar->values.size() == expected) return primvar;
        warnings.push_back(std::string(name) + " has " + std::to_string(primvar->values.size() / primvar->components) +
                           " values but " + interpolationName(primvar->interpolation) + " interpolation on this patch needs " +
                           std::to_string(expected / primvar->components) + "; ignored");
        return std::nullopt;
    }

    // What the tessellation's primvar starts as: constant as it is, uniform per face, else per vertex.
    static MeshPrimvar startOutput(const MeshPrimvar& in) {
        if (in.interpolation == OBSCURA_INTERPOLATION_CONSTANT) return in;
        return MeshPrimvar{{}, in.interpolation == OBSCURA_INTERPOLATION_UNIFORM ? OBSCURA_INTERPOLATION_UNIFORM
                                                                                 : OBSCURA_INTERPOLATION_VERTEX,
                           in.components};
    }

    // A vertex's value: vertex primvars through the surface's basis, varying ones bilinear
    // between the corners of the knot span.
    void appendVertex(MeshPrimvar& out, const MeshPrimvar& in, const PatchBasis& b, const Sample& u, const Sample& v) const {
        if (in.interpolation == OBSCURA_INTERPOLATION_VERTEX) {
            std::array<double, 4> sum{};
            combine(b, b.r, in.values, in.components, patch_.u.vertexCount, sum.data());
            for (size_t k = 0; k < in.components; ++k) out.values.push_back(float(sum[k]));
        } else if (in.interpolation == OBSCURA_INTERPOLATION_VARYING || in.interpolation == OBSCURA_INTERPOLATION_FACE_VARYING) {
            const size_t su = size_t(u.span - (patch_.u.order - 1)), sv = size_t(v.span - (patch_.v.order - 1));
            const size_t cornersU = size_t(patch_.u.spanCount()) + 1;
            const double a = fraction(patch_.u, u), c = fraction(patch_.v, v);
            for (size_t k = 0; k < in.components; ++k) {
                auto at = [&](size_t x, size_t y) { return double(in.values[((sv + y) * cornersU + su + x) * in.components + k]); };
                out.values.push_back(float((1 - c) * ((1 - a) * at(0, 0) + a * at(1, 0)) + c * ((1 - a) * at(0, 1) + a * at(1, 1))));
            }
        }
    }

    void appendFace(MeshPrimvar& out, const MeshPrimvar& in, size_t i, size_t j) const {
        const size_t su = size_t(us_.intervalSpan[i] - (patch_.u.order - 1));
        const size_t sv = size_t(vs_.intervalSpan[j] - (patch_.v.order - 1));
        const size_t element = sv * size_t(patch_.u.spanCount()) + su;
        for (size_t k = 0; k < in.components; ++k) out.values.push_back(in.values[element * in.components + k]);
    }

    // Where a sample lies within its whole knot span, 0 to 1.
    static double fraction(const NurbsDirection& d, const Sample& s) {
        const double lo = d.knots[size_t(s.span)], hi = d.knots[size_t(s.span + 1)];
        return (s.t - lo) / (hi - lo);
    }

    // dS/du x dS/dv, unit length, outwards for rightHanded. Where it vanishes (a pole, where a
    // whole row of control points meets), the normal just inside the span.
    Vec3 normalAt(const PatchBasis& b, const Sample& u, const Sample& v) const {
        Vec3 n = spanNormal(b, u, v);
        if (norm(n) <= 1e-9 * scale() * scale()) {
            auto inward = [](const Sample& s) { return s.t + (0.5 * (s.lo + s.hi) - s.t) * 1e-3; };
            n = spanNormal(patchBasis(patch_, basisAt(patch_.u, u.span, inward(u)), basisAt(patch_.v, v.span, inward(v))), u, v);
        }
        const double length = norm(n);
        if (!(length > 0.0)) return {0.0, 0.0, patch_.leftHanded ? -1.0 : 1.0};  // a patch of no area
        const double sign = patch_.leftHanded ? -1.0 : 1.0;
        return {sign * n[0] / length, sign * n[1] / length, sign * n[2] / length};
    }

    // The cross product of the partials with the parameter scaled to the drawn span (so its size
    // compares with the patch's).
    Vec3 spanNormal(const PatchBasis& b, const Sample& u, const Sample& v) const {
        Vec3 du = combinePoints(b, b.ru, patch_);
        Vec3 dv = combinePoints(b, b.rv, patch_);
        for (double& x : du) x *= u.hi - u.lo;
        for (double& x : dv) x *= v.hi - v.lo;
        return cross(du, dv);
    }

    // The control points' extent: what "vanishes" is measured against.
    double scale() const {
        if (scale_ < 0.0) {
            std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
            for (size_t i = 0; i + 2 < patch_.points.size(); i += 3)
                for (size_t k = 0; k < 3; ++k) {
                    lo[k] = std::min(lo[k], double(patch_.points[i + k]));
                    hi[k] = std::max(hi[k], double(patch_.points[i + k]));
                }
            scale_ = norm({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
        }
        return scale_;
    }

    const NurbsPatchInput& patch_;
    Samples us_, vs_;
    mutable double scale_ = -1.0;
};

std::string directionProblem(const NurbsDirection& d, char name) {
    const std::string n(1, name);
    if (d.order < 2 || d.order > kMaxNurbsOrder)
        return n + "Order is " + std::to_string(d.order) + "; it must be 2 to " + std::to_string(kMaxNurbsOrder);
    if (d.vertexCount < d.order)
        return n + "VertexCount is " + std::to_string(d.vertexCount) + "; it must be at least " + n + "Order (" +
               std::to_string(d.order) + ")";
    if (d.knots.size() != size_t(d.vertexCount + d.order))
        return n + "Knots has " + std::to_string(d.knots.size()) + " values but " + n + "VertexCount + " + n + "Order is " +
               std::to_string(d.vertexCount + d.order);
    for (size_t i = 1; i < d.knots.size(); ++i)
        if (d.knots[i] < d.knots[i - 1]) return n + "Knots decrease at [" + std::to_string(i) + "]";
    const double lo = d.knots[size_t(d.order - 1)], hi = d.knots[size_t(d.vertexCount)];
    if (!(hi > lo))
        return n + "Knots give an empty parameter range (" + n + "Knots[" + std::to_string(d.order - 1) + "] = " + n +
               "Knots[" + std::to_string(d.vertexCount) + "])";
    const bool authored = d.range[0] != 0.0 || d.range[1] != 0.0;
    if (authored && !(d.range[0] >= lo && d.range[1] <= hi && d.range[0] < d.range[1]))
        return n + "Range (" + std::to_string(d.range[0]) + ", " + std::to_string(d.range[1]) +
               ") is not an increasing interval within the knots' range (" + std::to_string(lo) + ", " + std::to_string(hi) + ")";
    return {};
}

}  // namespace

std::array<double, 2> NurbsDirection::drawnRange() const {
    if (range[0] != 0.0 || range[1] != 0.0) return range;
    return {knots[size_t(order - 1)], knots[size_t(vertexCount)]};
}

std::string nurbsPatchProblem(const NurbsPatchInput& patch) {
    if (std::string problem = directionProblem(patch.u, 'u'); !problem.empty()) return problem;
    if (std::string problem = directionProblem(patch.v, 'v'); !problem.empty()) return problem;
    const size_t points = size_t(patch.u.vertexCount) * size_t(patch.v.vertexCount);
    if (patch.points.size() != points * 3)
        return "points has " + std::to_string(patch.points.size() / 3) + " values but uVertexCount x vVertexCount is " +
               std::to_string(points);
    if (!patch.pointWeights.empty() && patch.pointWeights.size() != points)
        return "pointWeights has " + std::to_string(patch.pointWeights.size()) + " values but there are " +
               std::to_string(points) + " points";
    for (size_t i = 0; i < patch.pointWeights.size(); ++i)
        if (!(patch.pointWeights[i] > 0.0f))
            return "pointWeights[" + std::to_string(i) + "] is " + std::to_string(patch.pointWeights[i]) +
                   "; weights must be positive";
    return {};
}

std::array<int, 2> nurbsDrawnSpans(const NurbsPatchInput& patch) {
    return {int(samplesOf(patch.u, 1).intervalSpan.size()), int(samplesOf(patch.v, 1).intervalSpan.size())};
}

uint64_t nurbsTriangleCount(const NurbsPatchInput& patch, std::array<int, 2> steps) {
    const std::array<int, 2> spans = nurbsDrawnSpans(patch);
    return 2ull * uint64_t(spans[0]) * uint64_t(steps[0]) * uint64_t(spans[1]) * uint64_t(steps[1]);
}

std::array<double, 2> nurbsBendMagnitude(const NurbsPatchInput& patch) {
    const Samples us = samplesOf(patch.u, bendSamples(patch.u)), vs = samplesOf(patch.v, bendSamples(patch.v));
    std::array<double, 2> bend{0.0, 0.0};
    for (const Sample& v : vs.at)
        for (const Sample& u : us.at) {
            const SpanBasis bu = basisAt(patch.u, u.span, u.t), bv = basisAt(patch.v, v.span, v.t);
            // Homogeneous sums A = sum N w P, W = sum N w and their u and v derivatives to the second.
            std::array<V4, 5> sums{};  // value, d/du, d2/du2, d/dv, d2/dv2
            for (int j = 0; j < patch.v.order; ++j)
                for (int i = 0; i < patch.u.order; ++i) {
                    const size_t point = size_t(bv.first + j) * size_t(patch.u.vertexCount) + size_t(bu.first + i);
                    const double w = patch.pointWeights.empty() ? 1.0 : patch.pointWeights[point];
                    const V4 homogeneous{w * patch.points[3 * point], w * patch.points[3 * point + 1],
                                         w * patch.points[3 * point + 2], w};
                    const std::array<double, 5> c{bu.value[size_t(i)] * bv.value[size_t(j)],
                                                  bu.derivative[size_t(i)] * bv.value[size_t(j)],
                                                  bu.second[size_t(i)] * bv.value[size_t(j)],
                                                  bu.value[size_t(i)] * bv.derivative[size_t(j)],
                                                  bu.value[size_t(i)] * bv.second[size_t(j)]};
                    for (size_t s = 0; s < 5; ++s)
                        for (size_t k = 0; k < 4; ++k) sums[s][k] += c[s] * homogeneous[k];
                }
            // S'' = (A'' - 2 W' S' - W'' S) / W (The NURBS Book, eq. 4.8), per direction, span-normalised.
            const double W = sums[0][3];
            for (size_t direction = 0; direction < 2; ++direction) {
                const V4& first = sums[1 + 2 * direction];
                const V4& second = sums[2 + 2 * direction];
                const double length = direction == 0 ? u.hi - u.lo : v.hi - v.lo;
                Vec3 s2;
                for (size_t k = 0; k < 3; ++k) {
                    const double S = sums[0][k] / W, S1 = (first[k] - first[3] * S) / W;
                    s2[k] = (second[k] - 2 * first[3] * S1 - second[3] * S) / W;
                }
                bend[direction] = std::max(bend[direction], norm(s2) * length * length);
            }
        }
    return bend;
}

NurbsTessellation tessellateNurbsPatch(const NurbsPatchInput& patch, std::array<int, 2> steps) {
    return GridWriter(patch, steps).write();
}

}  // namespace obscura::delegate
