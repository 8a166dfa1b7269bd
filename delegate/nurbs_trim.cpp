#include "delegate/nurbs_trim.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

namespace obscura::delegate {
namespace {

// Polyline points per knot span of a curved trim curve, fewer over many spans so that no trim
// makes more than about kMaxTrimPoints points in all; a linear one needs its control points alone.
constexpr int kStepsPerSpan = 16;
constexpr size_t kMaxTrimPoints = 1 << 16;

NurbsDirectionNames namesOf(size_t curve) {
    const std::string at = "[" + std::to_string(curve) + "]";
    return {"trimCurve:orders" + at, "trimCurve:vertexCounts" + at, "the trimCurve:knots of curve " + std::to_string(curve),
            "trimCurve:ranges" + at};
}

// The curves one after another as B-spline directions (their knots and ranges).
std::vector<NurbsDirection> directionsOf(const NurbsTrimCurves& c) {
    std::vector<NurbsDirection> out;
    size_t knot = 0;
    for (size_t k = 0; k < c.orders.size(); ++k) {
        NurbsDirection d;
        d.order = c.orders[k];
        d.vertexCount = c.vertexCounts[k];
        const size_t n = size_t(std::max(d.order + d.vertexCount, 0));
        if (knot + n <= c.knots.size()) d.knots.assign(c.knots.begin() + std::ptrdiff_t(knot), c.knots.begin() + std::ptrdiff_t(knot + n));
        knot += n;
        if (k < c.ranges.size()) d.range = c.ranges[k];
        out.push_back(std::move(d));
    }
    return out;
}

double signedArea(const std::vector<std::array<double, 2>>& loop) {
    double twice = 0.0;
    for (size_t i = 0; i < loop.size(); ++i) {
        const auto& a = loop[i];
        const auto& b = loop[(i + 1) % loop.size()];
        twice += a[0] * b[1] - b[0] * a[1];
    }
    return 0.5 * twice;
}

}  // namespace

std::string nurbsTrimProblem(const NurbsTrimCurves& c) {
    int64_t curves = 0;
    for (size_t i = 0; i < c.counts.size(); ++i) {
        if (c.counts[i] < 1) return "trimCurve:counts[" + std::to_string(i) + "] is " + std::to_string(c.counts[i]) + "; a loop needs a curve";
        curves += c.counts[i];
    }
    auto perCurve = [&](const char* name, size_t size) {
        return std::string(name) + " has " + std::to_string(size) + " values but trimCurve:counts adds up to " +
               std::to_string(curves) + " curves";
    };
    if (c.orders.size() != size_t(curves)) return perCurve("trimCurve:orders", c.orders.size());
    if (c.vertexCounts.size() != size_t(curves)) return perCurve("trimCurve:vertexCounts", c.vertexCounts.size());
    if (!c.ranges.empty() && c.ranges.size() != size_t(curves)) return perCurve("trimCurve:ranges", c.ranges.size());
    for (size_t k = 0; k < c.orders.size(); ++k)
        if (std::string problem = nurbsOrderProblem(c.orders[k], c.vertexCounts[k], namesOf(k)); !problem.empty()) return problem;
    int64_t knots = 0, points = 0;
    for (size_t k = 0; k < c.orders.size(); ++k) {
        knots += int64_t(c.orders[k]) + c.vertexCounts[k];
        points += c.vertexCounts[k];
    }
    if (int64_t(c.knots.size()) != knots)
        return "trimCurve:knots has " + std::to_string(c.knots.size()) + " values but the curves' orders and vertex counts add up to " +
               std::to_string(knots);
    if (int64_t(c.points.size()) != points)
        return "trimCurve:points has " + std::to_string(c.points.size()) + " values but trimCurve:vertexCounts adds up to " +
               std::to_string(points);
    const std::vector<NurbsDirection> directions = directionsOf(c);
    for (size_t k = 0; k < directions.size(); ++k)
        if (std::string problem = nurbsDirectionProblem(directions[k], namesOf(k)); !problem.empty()) return problem;
    for (size_t i = 0; i < c.points.size(); ++i)
        if (!(c.points[i][2] > 0.0))
            return "trimCurve:points[" + std::to_string(i) + "] has weight " + std::to_string(c.points[i][2]) +
                   "; weights must be positive";
    return {};
}

NurbsTrimRegion::NurbsTrimRegion(const NurbsTrimCurves& c) {
    const std::vector<NurbsDirection> directions = directionsOf(c);
    int64_t spans = 0;
    for (const NurbsDirection& d : directions) spans += d.spanCount();
    const int steps = int(std::clamp<int64_t>(int64_t(kMaxTrimPoints) / std::max<int64_t>(spans, 1), 1, kStepsPerSpan));
    size_t curve = 0, firstPoint = 0;
    for (int32_t count : c.counts) {
        std::vector<Point> loop;
        for (int32_t n = 0; n < count; ++n, ++curve) {
            const NurbsDirection& d = directions[curve];
            const std::array<double, 2> range = d.drawnRange();
            const int spanSteps = d.order == 2 ? 1 : steps;
            // Each curve from the start of its range to just before its end, which the next curve
            // of the loop (or the loop's first point) continues from.
            for (int span = d.order - 1; span < d.vertexCount; ++span) {
                const double lo = std::max(d.knots[size_t(span)], range[0]), hi = std::min(d.knots[size_t(span + 1)], range[1]);
                if (!(hi > lo)) continue;
                for (int k = 0; k < spanSteps; ++k) {
                    const SpanBasis b = basisAt(d, span, lo + (hi - lo) * k / spanSteps);
                    double u = 0.0, v = 0.0, w = 0.0;
                    for (int i = 0; i < d.order; ++i) {
                        const std::array<double, 3>& p = c.points[firstPoint + size_t(b.first + i)];
                        u += b.value[size_t(i)] * p[0], v += b.value[size_t(i)] * p[1], w += b.value[size_t(i)] * p[2];
                    }
                    // A weight so small that the point leaves the doubles adds nothing a loop can bound.
                    if (std::isfinite(u / w) && std::isfinite(v / w)) loop.push_back({u / w, v / w});
                }
            }
            firstPoint += size_t(d.vertexCount);
        }
        if (loop.size() >= 3) loops_.push_back(std::move(loop));
    }
    // Loops that are all holes keep the patch's boundary as the outer one (as does no loop at all).
    double largest = 0.0, orientation = 1.0;
    for (const std::vector<Point>& loop : loops_) {
        const double area = signedArea(loop);
        if (std::abs(area) > largest) largest = std::abs(area), orientation = area;
    }
    outsideWinding_ = loops_.empty() || orientation < 0.0 ? 1 : 0;
}

NurbsTrimLine NurbsTrimRegion::line(int direction, double at, const std::vector<double>& along) const {
    const size_t x = direction == 0 ? 0 : 1, y = 1 - x;
    // The boundary's crossings of the line, each with the winding it adds about the points before
    // it on the line (the ray from a point along +x counts it): +1 where the boundary runs
    // counter-clockwise about them.
    struct Crossing {
        double position;
        int winding;
    };
    std::vector<Crossing> crossings;
    for (const std::vector<Point>& loop : loops_)
        for (size_t i = 0; i < loop.size(); ++i) {
            const Point& a = loop[i];
            const Point& b = loop[(i + 1) % loop.size()];
            const bool up = a[y] <= at && at < b[y], down = b[y] <= at && at < a[y];
            if (!up && !down) continue;
            const double position = a[x] + (at - a[y]) / (b[y] - a[y]) * (b[x] - a[x]);
            // Along +u a counter-clockwise loop's far side runs up (+v); along +v its far side runs
            // towards -u, so the sense flips with the axes.
            crossings.push_back({position, (up ? 1 : -1) * (direction == 0 ? 1 : -1)});
        }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) { return a.position < b.position; });
    // Winding about a point: the sum over crossings beyond it.
    int beyond = outsideWinding_;
    for (const Crossing& c : crossings) beyond += c.winding;
    NurbsTrimLine out;
    out.kept.resize(along.size());
    out.crossing.assign(along.empty() ? 0 : along.size() - 1, std::numeric_limits<double>::quiet_NaN());
    const double none = std::numeric_limits<double>::quiet_NaN();
    size_t next = 0;  // the first crossing not yet passed
    double lastPassed = none;
    for (size_t i = 0; i < along.size(); ++i) {
        const bool before = i > 0 && out.kept[i - 1];
        // The boundary met at the interval's start (passed with the previous position), then the
        // last change of side within it, else the last crossing within it.
        double flip = none, last = i > 0 && lastPassed == along[i - 1] ? lastPassed : none;
        for (; next < crossings.size() && crossings[next].position <= along[i]; ++next) {
            beyond -= crossings[next].winding;
            last = lastPassed = crossings[next].position;
            flip = (beyond > 0) != before ? last : none;
        }
        out.kept[i] = beyond > 0;
        // Where a neighbouring line sees the ends differ and this one does not (the boundary
        // through a grid point), the crossing is where this line meets the boundary.
        if (i > 0) out.crossing[i - 1] = std::isnan(flip) ? last : flip;
    }
    return out;
}

std::array<double, 2> NurbsTrimRegion::smallestLoop() const {
    std::array<double, 2> smallest{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    for (const std::vector<Point>& loop : loops_)
        for (size_t k = 0; k < 2; ++k) {
            const auto [lo, hi] = std::minmax_element(loop.begin(), loop.end(), [k](const Point& a, const Point& b) { return a[k] < b[k]; });
            smallest[k] = std::min(smallest[k], (*hi)[k] - (*lo)[k]);
        }
    return smallest;
}

}  // namespace obscura::delegate
