// OpenUSD's spline-valued attributes (TsSpline, OpenUSD 25.05): knots, curve type, extrapolation
// and an inner loop as authored in `.spline = { ... }`, and their value at any time as Ts
// evaluates it (pxr/base/ts/eval.cpp). Only scalar floating-point attributes carry splines.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace obscura::usda {

// How the segment after a knot runs to the next one (TsInterpMode); None: no value there.
enum class SplineInterpolation { None, Held, Linear, Curve };

// The value before the first knot or after the last (TsExtrapMode); None: no value there.
enum class SplineExtrapolationMode { None, Held, Linear, Sloped, LoopRepeat, LoopReset, LoopOscillate };

struct SplineExtrapolation {
    SplineExtrapolationMode mode = SplineExtrapolationMode::Held;
    double slope = 0.0;  // Sloped only
    bool isLooping() const { return mode >= SplineExtrapolationMode::LoopRepeat; }
    bool operator==(const SplineExtrapolation&) const = default;
};

// TsLoopParams: the knots in [protoStart, protoEnd) repeat numPreLoops times before and
// numPostLoops times after, each copy offset by valueOffset.
struct SplineLoop {
    double protoStart = 0.0, protoEnd = 0.0;
    int numPreLoops = 0, numPostLoops = 0;
    double valueOffset = 0.0;
    bool operator==(const SplineLoop&) const = default;
};

struct SplineKnot {
    double time = 0.0;
    double value = 0.0;
    std::optional<double> preValue;  // a dual-valued knot's value just before it ("pre & value")
    SplineInterpolation next = SplineInterpolation::Held;
    // Tangents in Ts's standard form: a width in time (Bezier only) and a slope.
    double preWidth = 0.0, preSlope = 0.0, postWidth = 0.0, postSlope = 0.0;
    double valueBefore() const { return preValue.value_or(value); }
    bool operator==(const SplineKnot&) const = default;
};

// What a spline may cost to evaluate and to sample, whatever a file authors: its inner loop unrolls
// at most this many knots (the readers report a spline beyond it and leave it out), and a sampled
// interval holding more repetitions of a looping extrapolation than this many sample times is
// sampled evenly at that many instead.
constexpr double kMaxUnrolledSplineKnots = 10000;
constexpr size_t kMaxSplineSampleTimes = 4096;

struct Spline {
    std::string valueType;  // the attribute's scalar type: "double", "float", "half", "timecode"
    bool hermite = false;   // curve segments are Hermite (tangent widths fixed at a third)
    SplineExtrapolation pre, post;
    std::optional<SplineLoop> loop;
    std::vector<SplineKnot> knots;  // authored, by time

    bool operator==(const Spline&) const = default;

    // The value at `time` (the post-side value at a knot, as UsdAttribute::Get reads it); no value
    // in a segment or extrapolation of mode None, or without knots.
    std::optional<double> evaluate(double time) const;
    // Whether the value can change over time.
    bool varies() const;
    // Times in [from, to] where the curve's shape changes (knots, inner-loop and, for a finite
    // interval, extrapolating-loop copies of them) and steps inside curved segments, sorted: what
    // a renderer samples to follow the curve, e.g. within a shutter interval.
    std::vector<double> sampleTimes(double from, double to) const;
    // This spline with its times mapped by t -> offset + scale * t (a layer offset; scale > 0).
    Spline retimed(double offset, double scale) const;
    // Why the readers leave this spline out (its inner loop unrolls more than
    // kMaxUnrolledSplineKnots knots), or empty.
    std::string innerLoopProblem() const;
};

// Whether a spline animates an attribute of this type: TsSpline's value types, and timecode,
// which UsdAttribute::SetSpline also takes.
bool splineAnimates(std::string_view typeName, bool isArray);

// A tangent's slope from Maya's form (ts/tangentConversions.cpp, eval.cpp's _GetCurveKnotSlope):
// its height over its Maya width (three times Ts's; a Hermite's is its segment's length), a
// pre-tangent's height negated; 0 without a width.
double slopeOfMayaTangent(bool isPre, double height, double mayaWidth);

}  // namespace obscura::usda
