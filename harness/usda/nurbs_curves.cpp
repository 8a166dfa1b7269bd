#include "harness/usda/nurbs_curves.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace obscura::usda {
namespace {

// The p + 1 basis functions that are not zero on one knot span, and their derivatives: entry j is
// the function of control point (span - p + j).
struct SpanBasis {
    std::vector<double> value, derivative;
};

// The B-spline basis of degree p on span s of the knots U (U[s] < U[s + 1]) at t in [U[s], U[s + 1]]
// (the span's polynomial, its ends included): the Cox-de Boor recursion (de Boor 1972, Cox 1972)
// in the triangular form of Piegl & Tiller, The NURBS Book (2nd ed.), algorithm A2.2; derivatives
// from the degree p - 1 functions by their eq. 2.7.
SpanBasis bsplineBasis(const double* U, size_t s, size_t p, double t) {
    std::vector<double> N(p + 1, 0.0), left(p + 1, 0.0), right(p + 1, 0.0), lower;
    N[0] = 1.0;
    for (size_t j = 1; j <= p; ++j) {
        if (j == p) lower.assign(N.begin(), N.begin() + long(p));  // degree p - 1, from control point s - p + 1
        left[j] = t - U[s + 1 - j];
        right[j] = U[s + j] - t;
        double saved = 0.0;
        for (size_t r = 0; r < j; ++r) {
            const double temp = N[r] / (right[r + 1] + left[j - r]);
            N[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        N[j] = saved;
    }
    // N'_{i,p} = p (N_{i,p-1} / (U[i+p] - U[i]) - N_{i+1,p-1} / (U[i+p+1] - U[i+1])); both
    // denominators span knot span s, so neither is zero.
    std::vector<double> dN(p + 1, 0.0);
    for (size_t j = 0; j <= p; ++j) {
        const size_t i = s - p + j;
        if (j >= 1) dN[j] += lower[j - 1] / (U[i + p] - U[i]);
        if (j + 1 <= p) dN[j] -= lower[j] / (U[i + p + 1] - U[i + 1]);
        dN[j] *= double(p);
    }
    return {std::move(N), std::move(dN)};
}

// The rational basis R_i = w_i N_i / W, W = sum w_j N_j, and its derivative
// R_i' = w_i (N_i' W - N_i W') / W^2 (The NURBS Book, eq. 4.2 and its derivative); `weights` of
// the span's control points, null for a polynomial curve (R = N).
SpanBasis rationalBasis(const double* U, size_t s, size_t p, double t, const double* weights) {
    SpanBasis basis = bsplineBasis(U, s, p, t);
    if (!weights) return basis;
    double W = 0.0, dW = 0.0;
    for (size_t j = 0; j <= p; ++j) {
        W += weights[j] * basis.value[j];
        dW += weights[j] * basis.derivative[j];
    }
    for (size_t j = 0; j <= p; ++j) {
        const double N = basis.value[j], dN = basis.derivative[j];
        basis.value[j] = weights[j] * N / W;
        basis.derivative[j] = weights[j] * (dN * W - N * dW) / (W * W);
    }
    return basis;
}

// A piece [t0, t1] of one span in Hermite form: its four Bezier control points as combinations of
// the span's control points.
std::array<std::vector<double>, 4> hermitePiece(const SpanBasis& start, const SpanBasis& end, double h) {
    std::array<std::vector<double>, 4> rows{start.value, start.value, end.value, end.value};
    for (size_t j = 0; j < start.value.size(); ++j) {
        rows[1][j] += h / 3.0 * start.derivative[j];
        rows[2][j] -= h / 3.0 * end.derivative[j];
    }
    return rows;
}

// The largest sum over the span's control points of |R_j(t) - H_j(t)|, H the Hermite pieces' basis.
// Both bases sum to 1, so the distance of the Bezier form from the curve, sum (R_j - H_j)(P_j - c),
// is at most that sum times max |P_j - c| for any centre c: this share of the radius of the
// smallest sphere around the span's control points, whatever the points are. Sampled at seven
// points inside each piece (the Hermite form is exact at the piece's ends).
double hermiteError(const double* U, size_t s, size_t p, double lo, double hi, int pieces, const double* weights) {
    double worst = 0.0;
    const double h = (hi - lo) / pieces;
    for (int piece = 0; piece < pieces; ++piece) {
        const double t0 = lo + h * piece;
        const auto rows = hermitePiece(rationalBasis(U, s, p, t0, weights), rationalBasis(U, s, p, t0 + h, weights), h);
        for (int k = 1; k < 8; ++k) {
            const double u = k / 8.0, v = 1.0 - u;
            const double bernstein[4] = {v * v * v, 3 * u * v * v, 3 * u * u * v, u * u * u};
            const SpanBasis exact = rationalBasis(U, s, p, t0 + h * u, weights);
            double sum = 0.0;
            for (size_t j = 0; j <= p; ++j) {
                double hermite = 0.0;
                for (size_t b = 0; b < 4; ++b) hermite += bernstein[b] * rows[b][j];
                sum += std::abs(exact.value[j] - hermite);
            }
            worst = std::max(worst, sum);
        }
    }
    return worst;
}

// Whether two combinations (weights over consecutive columns from a first one) are the same point
// of every curve: where a knot of full multiplicity makes the curve jump, they differ.
bool samePoint(size_t firstA, const std::vector<double>& a, size_t firstB, const std::vector<double>& b) {
    const size_t lo = std::min(firstA, firstB), hi = std::max(firstA + a.size(), firstB + b.size());
    for (size_t column = lo; column < hi; ++column) {
        const double wa = column >= firstA && column < firstA + a.size() ? a[column - firstA] : 0.0;
        const double wb = column >= firstB && column < firstB + b.size() ? b[column - firstB] : 0.0;
        if (std::abs(wa - wb) > 1e-9) return false;
    }
    return true;
}

std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", value);
    return text;
}

std::optional<AttributeProblem> validate(const NurbsCurvesData& c) {
    const size_t curves = c.curveVertexCounts.size();
    size_t points = 0, knots = 0;
    for (size_t i = 0; i < curves; ++i) {
        if (c.curveVertexCounts[i] < 0)
            return AttributeProblem{"curveVertexCounts", "curveVertexCounts[" + std::to_string(i) + "] is negative"};
        points += size_t(c.curveVertexCounts[i]);
    }
    if (points != c.pointCount)
        return AttributeProblem{"curveVertexCounts", "curveVertexCounts add up to " + std::to_string(points) + " but there are " +
                                                         std::to_string(c.pointCount) + " points"};
    if (c.order.size() != curves)
        return AttributeProblem{"order", "order has " + std::to_string(c.order.size()) + " values but there are " +
                                             std::to_string(curves) + " curves"};
    for (size_t i = 0; i < curves; ++i) {
        if (c.order[i] < 2 || c.order[i] > c.curveVertexCounts[i])
            return AttributeProblem{"order", "order[" + std::to_string(i) + "] = " + std::to_string(c.order[i]) +
                                                 " is outside [2, " + std::to_string(c.curveVertexCounts[i]) +
                                                 "] (2 to the curve's vertex count)"};
        knots += size_t(c.curveVertexCounts[i]) + size_t(c.order[i]);
    }
    if (c.knots.size() != knots)
        return AttributeProblem{"knots", "knots has " + std::to_string(c.knots.size()) + " values but the curves need " +
                                             std::to_string(knots) + " (vertex count + order each)"};
    if (!c.ranges.empty() && c.ranges.size() != 2 * curves)
        return AttributeProblem{"ranges", "ranges has " + std::to_string(c.ranges.size() / 2) + " values but there are " +
                                              std::to_string(curves) + " curves"};
    if (!c.pointWeights.empty() && c.pointWeights.size() != c.pointCount)
        return AttributeProblem{"pointWeights", "pointWeights has " + std::to_string(c.pointWeights.size()) +
                                                    " values but there are " + std::to_string(c.pointCount) + " points"};
    for (size_t i = 0; i < c.pointWeights.size(); ++i)
        if (!(c.pointWeights[i] > 0.0 && std::isfinite(c.pointWeights[i])))
            return AttributeProblem{"pointWeights", "pointWeights[" + std::to_string(i) + "] = " + number(c.pointWeights[i]) +
                                                        " is not a positive number"};
    for (size_t curve = 0, first = 0; curve < curves; first += size_t(c.curveVertexCounts[curve]) + size_t(c.order[curve]), ++curve) {
        const size_t n = size_t(c.curveVertexCounts[curve]), p = size_t(c.order[curve] - 1);
        const double* U = &c.knots[first];
        for (size_t k = 0; k < n + p + 1; ++k) {
            if (!std::isfinite(U[k]))
                return AttributeProblem{"knots", "knots[" + std::to_string(first + k) + "] is not a number"};
            if (k > 0 && U[k] < U[k - 1])
                return AttributeProblem{"knots", "knots decrease at knots[" + std::to_string(first + k) + "] (curve " +
                                                     std::to_string(curve) + ")"};
        }
        if (!(U[p] < U[n]))
            return AttributeProblem{"knots", "the knots of curve " + std::to_string(curve) + " leave no parameter range (knots[" +
                                                 std::to_string(first + p) + "] = knots[" + std::to_string(first + n) + "])"};
        if (c.ranges.empty()) continue;
        const double lo = c.ranges[2 * curve], hi = c.ranges[2 * curve + 1];
        if (!(lo < hi && lo >= U[p] && hi <= U[n]))
            return AttributeProblem{"ranges", "ranges[" + std::to_string(curve) + "] = (" + number(lo) + ", " + number(hi) +
                                                  ") is not an interval within the knots' (" + number(U[p]) + ", " +
                                                  number(U[n]) + ")"};
    }
    return std::nullopt;
}

}  // namespace

std::variant<BezierCurves, AttributeProblem> nurbsToBezier(const NurbsCurvesData& c) {
    if (auto problem = validate(c)) return *problem;
    BezierCurves out;
    out.authoredCurves = c.curveVertexCounts.size();
    out.vertex.inputCount = c.pointCount;
    size_t firstPoint = 0, firstKnot = 0, firstVarying = 0;
    for (size_t curve = 0; curve < c.curveVertexCounts.size(); ++curve) {
        const size_t n = size_t(c.curveVertexCounts[curve]), p = size_t(c.order[curve] - 1);
        const double* U = &c.knots[firstKnot];
        const double lo = c.ranges.empty() ? U[p] : c.ranges[2 * curve];
        const double hi = c.ranges.empty() ? U[n] : c.ranges[2 * curve + 1];
        const bool rational = !c.pointWeights.empty();
        // Where the last segment ended (first column, weights); none before the curve's first.
        std::optional<std::pair<size_t, std::vector<double>>> end;
        // The varying value at t: linear in the parameter between the ends of its span (UsdGeomCurves:
        // one varying value per segment end, nVerts - order + 2 per curve).
        auto varyingAt = [&](size_t s, double t) {
            const double f = (t - U[s]) / (U[s + 1] - U[s]);
            out.varying.addRow(firstVarying + (s - p), {1.0 - f, f});
        };
        for (size_t s = p; s < n; ++s) {
            const double t0 = std::max(U[s], lo), t1 = std::min(U[s + 1], hi);
            if (!(t0 < t1)) continue;
            const size_t firstColumn = firstPoint + s - p;
            const double* weights = rational ? &c.pointWeights[firstColumn] : nullptr;
            // Polynomial spans of order 4 or less are cubics: one Hermite segment is exact.
            int pieces = 1;
            if (rational || p > 3)
                while (pieces < kNurbsMaxPiecesPerSpan && hermiteError(U, s, p, t0, t1, pieces, weights) > kNurbsTolerance)
                    pieces *= 2;
            const double h = (t1 - t0) / pieces;
            for (int piece = 0; piece < pieces; ++piece) {
                const double a = t0 + h * piece, b = piece + 1 == pieces ? t1 : a + h;
                const SpanBasis start = rationalBasis(U, s, p, a, weights), finish = rationalBasis(U, s, p, b, weights);
                const auto rows = hermitePiece(start, finish, b - a);
                // A curve that jumps (a knot of full multiplicity) goes on as another Bezier curve.
                if (!end || !samePoint(end->first, end->second, firstColumn, rows[0])) {
                    out.curveVertexCounts.push_back(1);
                    out.sourceCurves.push_back(curve);
                    out.vertex.addRow(firstColumn, rows[0]);
                    varyingAt(s, a);
                }
                for (size_t r = 1; r < 4; ++r) out.vertex.addRow(firstColumn, rows[r]);
                varyingAt(s, b);
                out.curveVertexCounts.back() += 3;
                end = std::pair{firstColumn, rows[3]};
            }
        }
        firstPoint += n;
        firstKnot += n + p + 1;
        firstVarying += n - p + 1;
    }
    out.varying.inputCount = firstVarying;
    out.positions = out.vertex;
    return out;
}

std::variant<BezierCurves, AttributeProblem> nurbsCurvesAsBezier(const Prim& prim, double time) {
    auto numbers = [&](const char* name) {
        const Attribute* attribute = prim.attribute(name);
        auto value = attribute ? attribute->evaluate(time) : std::nullopt;
        return value ? value->numbers.vector() : std::vector<double>{};
    };
    auto integers = [&](const char* name) {
        std::vector<int> out;
        for (double n : numbers(name)) out.push_back(n >= -2147483648.0 && n <= 2147483647.0 ? int(n) : -1);
        return out;
    };
    NurbsCurvesData data;
    data.curveVertexCounts = integers("curveVertexCounts");
    data.order = integers("order");
    data.knots = numbers("knots");
    data.ranges = numbers("ranges");
    data.pointWeights = numbers("pointWeights");
    data.pointCount = numbers("points").size() / 3;
    return nurbsToBezier(data);
}

}  // namespace obscura::usda
