// Spline evaluation after OpenUSD's Ts (pxr/base/ts/eval.cpp, splineData.cpp, regressionPreventer).
#include "harness/usda/spline.h"

#include <algorithm>
#include <cmath>

namespace obscura::usda {

namespace {

// Which side of a knot a time is read on: a dual-valued knot, or one ending a held segment, has
// one value just before it and another at it.
enum class Side { Before, At };

constexpr int kCurveSteps = 4;  // samples per curved segment offered to renderers

// The knots with the inner loop unrolled, as Ts bakes it (TsLoopParams): knots inside the looped
// interval other than the prototype's are shadowed, the prototype [protoStart, protoEnd) repeats
// with its value offset, and a copy of its start knot closes the last iteration. A loop without
// a knot at protoStart, an empty prototype or no iterations does nothing (Ts_SplineData::HasInnerLoops).
// The knots of the inner loop's prototype, [protoStart, protoEnd).
size_t prototypeKnots(const Spline& spline) {
    const SplineLoop& loop = *spline.loop;
    return size_t(std::count_if(spline.knots.begin(), spline.knots.end(), [&](const SplineKnot& k) {
        return k.time >= loop.protoStart && k.time < loop.protoEnd;
    }));
}

// How many knots the inner loop adds when unrolled.
double unrolledLoopKnots(const Spline& spline) {
    const SplineLoop& loop = *spline.loop;
    return double(prototypeKnots(spline)) *
           (double(std::max(loop.numPreLoops, 0)) + double(std::max(loop.numPostLoops, 0)) + 1.0);
}

std::vector<SplineKnot> unrolledKnots(const Spline& spline) {
    // The readers leave out splines whose loop would unroll further (innerLoopProblem).
    if (!spline.loop || unrolledLoopKnots(spline) > kMaxUnrolledSplineKnots) return spline.knots;
    const SplineLoop& loop = *spline.loop;
    const int preLoops = std::max(loop.numPreLoops, 0), postLoops = std::max(loop.numPostLoops, 0);
    const auto start = std::find_if(spline.knots.begin(), spline.knots.end(),
                                    [&](const SplineKnot& k) { return k.time == loop.protoStart; });
    if (loop.protoEnd <= loop.protoStart || (preLoops == 0 && postLoops == 0) || start == spline.knots.end())
        return spline.knots;
    const double span = loop.protoEnd - loop.protoStart;
    const double loopedStart = loop.protoStart - preLoops * span, loopedEnd = loop.protoEnd + postLoops * span;
    auto copy = [&](const SplineKnot& knot, int iteration) {
        SplineKnot shifted = knot;
        shifted.time += iteration * span;
        shifted.value += iteration * loop.valueOffset;
        if (shifted.preValue) *shifted.preValue += iteration * loop.valueOffset;
        return shifted;
    };
    std::vector<SplineKnot> out;
    for (const SplineKnot& knot : spline.knots)
        if (knot.time < loopedStart) out.push_back(knot);
    for (int iteration = -preLoops; iteration <= postLoops; ++iteration)
        for (auto k = start; k != spline.knots.end() && k->time < loop.protoEnd; ++k) out.push_back(copy(*k, iteration));
    out.push_back(copy(*start, postLoops + 1));
    for (const SplineKnot& knot : spline.knots)
        if (knot.time > loopedEnd) out.push_back(knot);
    return out;
}

double segmentSlope(const SplineKnot& begin, const SplineKnot& end) {
    return (end.valueBefore() - begin.value) / (end.time - begin.time);
}

// Cubic Bezier in power form from its control points.
struct Cubic {
    double a, b, c, d;
    static Cubic fromPoints(double p0, double p1, double p2, double p3) {
        return {-p0 + 3 * p1 - 3 * p2 + p3, 3 * p0 - 6 * p1 + 3 * p2, -3 * p0 + 3 * p1, p0};
    }
    double at(double t) const { return ((a * t + b) * t + c) * t + d; }
    double slopeAt(double t) const { return (3 * a * t + 2 * b) * t + c; }
};

// A Bezier segment whose tangents reach so far that time would run backwards is evaluated with
// both tangents shortened by one factor until it just does not (Ts's Keep Ratio anti-regression).
// With widths a and b as fractions of the segment, time is monotonic when a + b <= 1 or inside
// the ellipse a^2 + b^2 + ab - 2a - 2b + 1 <= 0 (through (1,0), (4/3,1/3), (1,1)...); along the
// ray s * (a, b) the ellipse is left at s = (a + b + sqrt(ab)) / (a^2 + b^2 + ab).
void deregress(double span, double& preWidth, double& postWidth) {
    const double a = postWidth / span, b = preWidth / span;
    if (a + b <= 1.0) return;
    const double scale = (a + b + std::sqrt(a * b)) / (a * a + b * b + a * b);
    if (scale >= 1.0) return;
    postWidth *= scale;
    preWidth *= scale;
}

double bezier(const SplineKnot& begin, const SplineKnot& end, double time) {
    double postWidth = begin.postWidth, preWidth = end.preWidth;
    deregress(end.time - begin.time, preWidth, postWidth);
    const Cubic x = Cubic::fromPoints(begin.time, begin.time + postWidth, end.time - preWidth, end.time);
    const double endValue = end.valueBefore();
    const Cubic y = Cubic::fromPoints(begin.value, begin.value + postWidth * begin.postSlope,
                                      endValue - preWidth * end.preSlope, endValue);
    // x(t) is monotonic on [0, 1]: Newton steps kept inside a shrinking bracket.
    double lo = 0.0, hi = 1.0, t = (time - begin.time) / (end.time - begin.time);
    for (int i = 0; i < 64 && hi - lo > 1e-15; ++i) {
        const double error = x.at(t) - time;
        if (error == 0.0) break;
        (error < 0.0 ? lo : hi) = t;
        const double slope = x.slopeAt(t);
        const double step = slope > 0.0 ? t - error / slope : lo - 1.0;
        t = step > lo && step < hi ? step : 0.5 * (lo + hi);
    }
    return y.at(t);
}

// Cubic Hermite on the segment's unit interval, slopes scaled to it (Ts's _EvalHermite).
double hermite(const SplineKnot& begin, const SplineKnot& end, double time) {
    const double span = end.time - begin.time;
    const double u = (time - begin.time) / span;
    const double rise = end.valueBefore() - begin.value;
    const double m0 = begin.postSlope * span, m1 = end.preSlope * span;
    const double a = -2 * rise + m0 + m1, b = 3 * rise - 2 * m0 - m1;
    return ((a * u + b) * u + m0) * u + begin.value;
}

class Evaluator {
public:
    explicit Evaluator(const Spline& spline) : spline_(spline), knots_(unrolledKnots(spline)) {}

    std::optional<double> at(double time, Side side) const {
        if (knots_.empty()) return std::nullopt;
        double valueOffset = 0.0;
        resolveLoopingExtrapolation(time, side, valueOffset);
        const std::optional<double> value = unlooped(time, side);
        if (!value) return std::nullopt;
        return *value + valueOffset;
    }

private:
    // Outside the knots, a looping extrapolation reads the knots' span again: moved into it, with
    // the value offset of whole repeats, or mirrored in time for odd oscillations (Ts's
    // _LoopResolver::_DoExtrap). Each end loops in its own mode.
    // XXX: Ts (25.05 to 26.x) reads both ends' repeat and oscillate modes from the pre-extrapolation;
    // here each end follows its own, as TsExtrapolation documents.
    void resolveLoopingExtrapolation(double& time, Side& side, double& valueOffset) const {
        if (knots_.size() < 2) return;
        const double first = knots_.front().time, last = knots_.back().time;
        // The knots' own interval: [first, last) read after a time, (first, last] before it.
        const bool inside = side == Side::At ? time >= first && time < last : time > first && time <= last;
        if (inside) return;
        const bool isPre = spline_.pre.isLooping() && time < last;
        const bool isPost = !isPre && spline_.post.isLooping() && time > first;
        if (!isPre && !isPost) return;
        const SplineExtrapolationMode mode = (isPre ? spline_.pre : spline_.post).mode;
        const double span = last - first;
        const double iterations = (isPre ? first - time : time - last) / span;
        const int whole = static_cast<int>(iterations);
        // Exactly at an iteration boundary the near side belongs to one iteration less.
        const bool shortHop = whole == iterations && (isPre ? side == Side::At : side == Side::Before);
        const int hop = (shortHop ? whole : whole + 1) * (isPre ? 1 : -1);
        time += hop * span;
        if (mode == SplineExtrapolationMode::LoopRepeat) {
            valueOffset -= hop * (knots_.back().value - knots_.front().valueBefore());
        } else if (mode == SplineExtrapolationMode::LoopOscillate && hop % 2 != 0) {
            time = first + (span - (time - first));
            side = side == Side::At ? Side::Before : Side::At;
        }
    }

    // The slope of a non-looping extrapolation (Ts's _GetExtrapolationSlope); a looping mode left
    // here (one knot) is flat.
    std::optional<double> extrapolationSlope(bool isPre) const {
        const SplineExtrapolation& extrapolation = isPre ? spline_.pre : spline_.post;
        switch (extrapolation.mode) {
        case SplineExtrapolationMode::None: return std::nullopt;
        case SplineExtrapolationMode::Sloped: return extrapolation.slope;
        case SplineExtrapolationMode::Linear: break;
        default: return 0.0;
        }
        if (knots_.size() < 2) return 0.0;
        const SplineKnot& end = isPre ? knots_.front() : knots_.back();
        const SplineKnot& begin = isPre ? knots_.front() : knots_[knots_.size() - 2];
        const SplineKnot& segmentEnd = isPre ? knots_[1] : knots_.back();
        if (end.preValue) return 0.0;
        switch (begin.next) {
        case SplineInterpolation::Linear: return segmentSlope(begin, segmentEnd);
        case SplineInterpolation::Curve: return isPre ? end.postSlope : end.preSlope;
        default: return 0.0;
        }
    }

    std::optional<double> unlooped(double time, Side side) const {
        const auto next = std::lower_bound(knots_.begin(), knots_.end(), time,
                                           [](const SplineKnot& k, double t) { return k.time < t; });
        if (next != knots_.end() && next->time == time) {
            const bool first = next == knots_.begin(), last = next + 1 == knots_.end();
            if (side == Side::Before) {
                if (first) return spline_.pre.mode == SplineExtrapolationMode::None ? std::nullopt : std::optional(next->valueBefore());
                const SplineKnot& previous = *(next - 1);
                if (previous.next == SplineInterpolation::None) return std::nullopt;
                if (previous.next == SplineInterpolation::Held) return previous.value;
                return next->valueBefore();
            }
            if (last ? spline_.post.mode == SplineExtrapolationMode::None : next->next == SplineInterpolation::None)
                return std::nullopt;
            return next->value;
        }
        if (next == knots_.begin()) {
            const std::optional<double> slope = extrapolationSlope(true);
            if (!slope) return std::nullopt;
            return next->valueBefore() - *slope * (next->time - time);
        }
        const SplineKnot& previous = *(next - 1);
        if (next == knots_.end()) {
            const std::optional<double> slope = extrapolationSlope(false);
            if (!slope) return std::nullopt;
            return previous.value + *slope * (time - previous.time);
        }
        switch (previous.next) {
        case SplineInterpolation::None: return std::nullopt;
        case SplineInterpolation::Held: return previous.value;
        case SplineInterpolation::Linear: return previous.value + segmentSlope(previous, *next) * (time - previous.time);
        case SplineInterpolation::Curve:
            return spline_.hermite ? hermite(previous, *next, time) : bezier(previous, *next, time);
        }
        return std::nullopt;
    }

    const Spline& spline_;
    std::vector<SplineKnot> knots_;
};

}  // namespace

std::optional<double> Spline::evaluate(double time) const {
    return Evaluator(*this).at(time, Side::At);
}

bool Spline::varies() const {
    auto slopes = [](const SplineExtrapolation& e) { return e.mode == SplineExtrapolationMode::Sloped && e.slope != 0.0; };
    return unrolledKnots(*this).size() > 1 || (!knots.empty() && (slopes(pre) || slopes(post)));
}

std::vector<double> Spline::sampleTimes(double from, double to) const {
    const std::vector<SplineKnot> unrolled = unrolledKnots(*this);
    std::vector<double> times;
    if (unrolled.empty() || !varies() || from > to) return times;
    // The knots' own times and steps inside their curved segments, for one pass over the knots.
    std::vector<double> pass;
    for (size_t i = 0; i < unrolled.size(); ++i) {
        pass.push_back(unrolled[i].time);
        if (i + 1 < unrolled.size() && unrolled[i].next == SplineInterpolation::Curve)
            for (int step = 1; step < kCurveSteps; ++step)
                pass.push_back(unrolled[i].time + (unrolled[i + 1].time - unrolled[i].time) * step / kCurveSteps);
    }
    auto keep = [&](double t) {
        if (t >= from && t <= to) times.push_back(t);
    };
    const double first = unrolled.front().time, last = unrolled.back().time, span = last - first;
    const bool loopsBefore = pre.isLooping() && span > 0.0 && std::isfinite(from) && from < first;
    const bool loopsAfter = post.isLooping() && span > 0.0 && std::isfinite(to) && to > last;
    const double lowest = loopsBefore ? -std::ceil((first - from) / span) : 0.0;
    const double highest = loopsAfter ? std::ceil((to - last) / span) : 0.0;
    if ((highest - lowest + 1.0) * double(pass.size()) > double(kMaxSplineSampleTimes)) {
        // More repetitions than samples: the interval evenly (its ends are finite where it loops).
        const double lo = loopsBefore ? from : std::max(from, first), hi = loopsAfter ? to : std::min(to, last);
        for (size_t k = 0; k < kMaxSplineSampleTimes; ++k)
            keep(lo + (hi - lo) * double(k) / double(kMaxSplineSampleTimes - 1));
    } else {
        for (double iteration = lowest; iteration <= highest; iteration += 1.0)
            for (double t : pass) keep(t + iteration * span);
    }
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    return times;
}

std::string Spline::innerLoopProblem() const {
    if (!loop || unrolledLoopKnots(*this) <= kMaxUnrolledSplineKnots) return {};
    const long long times = (long long)std::max(loop->numPreLoops, 0) + std::max(loop->numPostLoops, 0) + 1;
    return "its inner loop repeats " + std::to_string(prototypeKnots(*this)) + " knots " + std::to_string(times) +
           " times, more than the " + std::to_string(int(kMaxUnrolledSplineKnots)) + " knots a spline may unroll";
}

Spline Spline::retimed(double offset, double scale) const {
    if (offset == 0.0 && scale == 1.0) return *this;
    Spline out = *this;
    for (SplineKnot& knot : out.knots) {
        knot.time = offset + scale * knot.time;
        knot.preWidth *= scale;
        knot.postWidth *= scale;
        knot.preSlope /= scale;
        knot.postSlope /= scale;
    }
    out.pre.slope /= scale;
    out.post.slope /= scale;
    if (out.loop) {
        out.loop->protoStart = offset + scale * out.loop->protoStart;
        out.loop->protoEnd = offset + scale * out.loop->protoEnd;
    }
    return out;
}

bool splineAnimates(std::string_view typeName, bool isArray) {
    return !isArray && (typeName == "double" || typeName == "float" || typeName == "half" || typeName == "timecode");
}

double slopeOfMayaTangent(bool isPre, double height, double mayaWidth) {
    if (!(mayaWidth > 0.0)) return 0.0;
    return (isPre ? -height : height) / mayaWidth;
}

}  // namespace obscura::usda
