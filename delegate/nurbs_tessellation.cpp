#include "delegate/nurbs_tessellation.h"

#include "delegate/nurbs_basis.h"

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
        color_ = checked(patch_.displayColor, "primvars:displayColor", out.warnings);
        opacity_ = checked(patch_.displayOpacity, "primvars:displayOpacity", out.warnings);
        st_ = checked(patch_.st, "primvars:st", out.warnings);
        if (color_) mesh.displayColor = startOutput(*color_);
        if (opacity_) mesh.displayOpacity = startOutput(*opacity_);
        mesh.st = st_ ? startOutput(*st_) : MeshPrimvar{{}, OBSCURA_INTERPOLATION_VERTEX, 2};
        for (const Sample& v : vs_.at)
            for (const Sample& u : us_.at) appendVertex(mesh, u, v);
        if (patch_.trimCurves.empty()) {
            const int32_t row = int32_t(us_.at.size());
            for (size_t j = 0; j < vs_.intervalSpan.size(); ++j)
                for (size_t i = 0; i < us_.intervalSpan.size(); ++i) {
                    // Counter-clockwise in (u, v): (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1).
                    const int32_t corner = int32_t(j) * row + int32_t(i);
                    appendFace(mesh, {corner, corner + 1, corner + row + 1, corner + row}, i, j);
                }
        } else {
            writeTrimmedFaces(mesh);
        }
        return out;
    }

private:
    // The surface's point, normal and primvars at one parameter pair (`u` and `v` carry their knot
    // spans).
    void appendVertex(MeshInput& mesh, const Sample& u, const Sample& v) const {
        const PatchBasis b = patchBasis(patch_, basisAt(patch_.u, u.span, u.t), basisAt(patch_.v, v.span, v.t));
        for (double x : combinePoints(b, b.r, patch_)) mesh.points.push_back(float(x));
        for (double n : normalAt(b, u, v)) mesh.normals->values.push_back(float(n));
        if (st_) {
            appendVertex(*mesh.st, *st_, b, u, v);
        } else {
            const std::array<double, 2> rangeU = patch_.u.drawnRange(), rangeV = patch_.v.drawnRange();
            mesh.st->values.insert(mesh.st->values.end(), {float((u.t - rangeU[0]) / (rangeU[1] - rangeU[0])),
                                                           float((v.t - rangeV[0]) / (rangeV[1] - rangeV[0]))});
        }
        if (color_) appendVertex(*mesh.displayColor, *color_, b, u, v);
        if (opacity_) appendVertex(*mesh.displayOpacity, *opacity_, b, u, v);
    }

    // A face of cell (i, j) through `corners`, with the cell's uniform primvars.
    void appendFace(MeshInput& mesh, const std::vector<int32_t>& corners, size_t i, size_t j) const {
        mesh.faceVertexCounts.push_back(int32_t(corners.size()));
        mesh.faceVertexIndices.insert(mesh.faceVertexIndices.end(), corners.begin(), corners.end());
        for (auto [input, output] : {std::pair{&color_, &mesh.displayColor}, std::pair{&opacity_, &mesh.displayOpacity},
                                     std::pair{&st_, &mesh.st}})
            if (*input && (*input)->interpolation == OBSCURA_INTERPOLATION_UNIFORM) appendUniform(**output, **input, i, j);
    }

    // The grid's cells cut by the trim curves (marching squares): each cell keeps its corners on
    // the kept side and, where an edge's ends differ, the point where the trim boundary crosses
    // that edge (exact, from the boundary's polyline), evaluated on the surface; within a cell the
    // boundary runs straight between its crossings.
    void writeTrimmedFaces(MeshInput& mesh) const {
        const NurbsTrimRegion region(patch_.trimCurves);
        std::vector<double> us, vs;
        for (const Sample& u : us_.at) us.push_back(u.t);
        for (const Sample& v : vs_.at) vs.push_back(v.t);
        std::vector<NurbsTrimLine> rows, columns;
        for (double v : vs) rows.push_back(region.line(0, v, us));
        for (double u : us) columns.push_back(region.line(1, u, vs));
        const int32_t row = int32_t(us.size());
        // The crossing vertex of each row interval (i, j) and column interval (i, j), made once.
        std::vector<int32_t> rowCrossing(rows.size() * (us.size() - 1), -1), columnCrossing(columns.size() * (vs.size() - 1), -1);
        auto crossingVertex = [&](bool alongU, size_t i, size_t j) {
            int32_t& index = alongU ? rowCrossing[j * (us.size() - 1) + i] : columnCrossing[i * (vs.size() - 1) + j];
            if (index < 0) {
                index = int32_t(mesh.points.size() / 3);
                Sample u = alongU ? us_.at[i + 1] : us_.at[i], v = alongU ? vs_.at[j] : vs_.at[j + 1];
                const double t = alongU ? rows[j].crossing[i] : columns[i].crossing[j];
                // A column that ties with a row at a corner may see no change where the row does.
                const double lo = alongU ? us[i] : vs[j], hi = alongU ? us[i + 1] : vs[j + 1];
                (alongU ? u : v).t = std::isnan(t) ? 0.5 * (lo + hi) : t;
                appendVertex(mesh, u, v);
            }
            return index;
        };
        for (size_t j = 0; j + 1 < vs.size(); ++j)
            for (size_t i = 0; i + 1 < us.size(); ++i) {
                // Counter-clockwise in (u, v); the edge after each corner: bottom (row j), right
                // (column i + 1), top (row j + 1), left (column i).
                const std::array<std::array<size_t, 2>, 4> corner{{{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
                auto kept = [&](size_t k) { return rows[corner[k][1]].kept[corner[k][0]] != 0; };
                std::vector<int32_t> face;
                for (size_t k = 0; k < 4; ++k) {
                    if (kept(k)) face.push_back(int32_t(corner[k][1]) * row + int32_t(corner[k][0]));
                    if (kept(k) == kept((k + 1) % 4)) continue;
                    if (k == 0 || k == 2) face.push_back(crossingVertex(true, i, k == 0 ? j : j + 1));
                    else face.push_back(crossingVertex(false, k == 1 ? i + 1 : i, j));
                }
                if (face.size() >= 3) appendFace(mesh, face, i, j);
            }
    }

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

    void appendUniform(MeshPrimvar& out, const MeshPrimvar& in, size_t i, size_t j) const {
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
    std::optional<MeshPrimvar> color_, opacity_, st_;  // the patch's, where their counts fit
    mutable double scale_ = -1.0;
};

}  // namespace

std::string nurbsPatchProblem(const NurbsPatchInput& patch) {
    if (std::string problem = nurbsDirectionProblem(patch.u, {"uOrder", "uVertexCount", "uKnots", "uRange"}); !problem.empty()) return problem;
    if (std::string problem = nurbsDirectionProblem(patch.v, {"vOrder", "vVertexCount", "vKnots", "vRange"}); !problem.empty()) return problem;
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
    return nurbsTrimProblem(patch.trimCurves);
}

namespace {

// The widest drawn knot span of a direction, in parameter.
double widestSpan(const NurbsDirection& d) {
    const Samples spans = samplesOf(d, 1);
    double widest = 0.0;
    for (size_t i = 0; i + 1 < spans.at.size(); ++i) widest = std::max(widest, spans.at[i + 1].t - spans.at[i].t);
    return widest;
}

// Object units per unit of parameter along u (0) or v (1): the control net's rows (or columns),
// their mean length over the knots' valid range.
double unitsPerParameter(const NurbsPatchInput& patch, size_t k) {
    const NurbsDirection& along = k == 0 ? patch.u : patch.v;
    const int lines = k == 0 ? patch.v.vertexCount : patch.u.vertexCount;
    double length = 0.0;
    for (int line = 0; line < lines; ++line)
        for (int i = 0; i + 1 < along.vertexCount; ++i) {
            auto point = [&](int at) {
                const size_t index = k == 0 ? size_t(line) * size_t(patch.u.vertexCount) + size_t(at)
                                            : size_t(at) * size_t(patch.u.vertexCount) + size_t(line);
                return Vec3{patch.points[3 * index], patch.points[3 * index + 1], patch.points[3 * index + 2]};
            };
            const Vec3 a = point(i), b = point(i + 1);
            length += norm({b[0] - a[0], b[1] - a[1], b[2] - a[2]});
        }
    const double range = along.knots[size_t(along.vertexCount)] - along.knots[size_t(along.order - 1)];
    return length / std::max(lines, 1) / range;
}

}  // namespace

std::array<int, 2> nurbsTrimSteps(const NurbsPatchInput& patch) {
    if (patch.trimCurves.empty()) return {1, 1};
    const std::array<double, 2> smallest = NurbsTrimRegion(patch.trimCurves).smallestLoop();
    std::array<int, 2> steps{1, 1};
    for (size_t k = 0; k < 2; ++k) {
        const double widest = widestSpan(k == 0 ? patch.u : patch.v);
        if (smallest[k] > 0.0 && std::isfinite(smallest[k]))
            steps[k] = int(std::clamp(std::ceil(kTrimCellsPerLoop * widest / smallest[k]), 1.0, double(kMaxTrimStepsPerSpan)));
    }
    return steps;
}

std::array<double, 2> nurbsTrimBend(const NurbsPatchInput& patch) {
    if (patch.trimCurves.empty()) return {0.0, 0.0};
    const std::array<double, 2> smallest = NurbsTrimRegion(patch.trimCurves).smallestLoop();
    const std::array<double, 2> units{unitsPerParameter(patch, 0), unitsPerParameter(patch, 1)};
    const double radius = 0.5 * std::min(smallest[0] * units[0], smallest[1] * units[1]);
    if (!(radius > 0.0) || !std::isfinite(radius)) return {0.0, 0.0};
    std::array<double, 2> bend{};
    for (size_t k = 0; k < 2; ++k) {
        const double span = widestSpan(k == 0 ? patch.u : patch.v) * units[k];
        bend[k] = span * span / radius;
    }
    return bend;
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
