#include "delegate/nurbs_basis.h"

namespace obscura::delegate {
namespace {

double ratio(double num, double den) { return den > 0.0 ? num / den : 0.0; }  // 0/0 of coincident knots: 0

// d/dt of the degree-`degree` functions of `span` from (the derivatives of) the degree - 1 ones
// (The NURBS Book, eq. 2.7; linear in them, so applied to first derivatives it gives second ones).
NurbsFunctions derivativeOf(const NurbsFunctions& lower, int degree, int span, const std::vector<double>& U) {
    NurbsFunctions out{};
    for (int k = 0; degree >= 1 && k <= degree; ++k) {
        const int i = span - degree + k;
        if (k >= 1) out[size_t(k)] += ratio(degree * lower[size_t(k - 1)], U[size_t(i + degree)] - U[size_t(i)]);
        if (k < degree) out[size_t(k)] -= ratio(degree * lower[size_t(k)], U[size_t(i + degree + 1)] - U[size_t(i + 1)]);
    }
    return out;
}

}  // namespace

std::array<double, 2> NurbsDirection::drawnRange() const {
    if (range[0] != 0.0 || range[1] != 0.0) return range;
    return {knots[size_t(order - 1)], knots[size_t(vertexCount)]};
}

std::string nurbsOrderProblem(int order, int vertexCount, const NurbsDirectionNames& n) {
    if (order < 2 || order > kMaxNurbsOrder)
        return n.order + " is " + std::to_string(order) + "; it must be 2 to " + std::to_string(kMaxNurbsOrder);
    if (vertexCount < order)
        return n.vertexCount + " is " + std::to_string(vertexCount) + "; it must be at least " + n.order + " (" +
               std::to_string(order) + ")";
    return {};
}

std::string nurbsDirectionProblem(const NurbsDirection& d, const NurbsDirectionNames& n) {
    if (std::string problem = nurbsOrderProblem(d.order, d.vertexCount, n); !problem.empty()) return problem;
    if (d.knots.size() != size_t(d.vertexCount + d.order))
        return n.knots + " has " + std::to_string(d.knots.size()) + " values but " + n.vertexCount + " + " + n.order +
               " is " + std::to_string(d.vertexCount + d.order);
    for (size_t i = 1; i < d.knots.size(); ++i)
        if (d.knots[i] < d.knots[i - 1]) return n.knots + " decrease at [" + std::to_string(i) + "]";
    const double lo = d.knots[size_t(d.order - 1)], hi = d.knots[size_t(d.vertexCount)];
    if (!(hi > lo))
        return n.knots + " give an empty parameter range (" + n.knots + "[" + std::to_string(d.order - 1) + "] = " +
               n.knots + "[" + std::to_string(d.vertexCount) + "])";
    const bool authored = d.range[0] != 0.0 || d.range[1] != 0.0;
    if (authored && !(d.range[0] >= lo && d.range[1] <= hi && d.range[0] < d.range[1]))
        return n.range + " (" + std::to_string(d.range[0]) + ", " + std::to_string(d.range[1]) +
               ") is not an increasing interval within the knots' range (" + std::to_string(lo) + ", " + std::to_string(hi) + ")";
    return {};
}

// Cox-de Boor (The NURBS Book, eq. 2.5), degree by degree.
SpanBasis basisAt(const NurbsDirection& d, int span, double t) {
    const int p = d.order - 1;
    const std::vector<double>& U = d.knots;
    NurbsFunctions N{}, degreeLess1{}, degreeLess2{};
    N[0] = 1.0;
    for (int degree = 1; degree <= p; ++degree) {
        degreeLess2 = degreeLess1;
        degreeLess1 = N;
        NurbsFunctions next{};
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

}  // namespace obscura::delegate
