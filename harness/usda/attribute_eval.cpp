// Attribute::evaluate: USD's value resolution at a time code for one composed attribute.
#include <algorithm>
#include <cmath>
#include <iterator>

#include "harness/usda/stage.h"
#include "harness/usda/value_types.h"

namespace obscura::usda {

namespace {

enum class Blend { Held, Linear, Slerp };

Blend blendOf(const Value& value) {
    const ValueType* type = findValueType(value.typeName);
    if (!type || type->scalar != ScalarKind::Real) return Blend::Held;
    return type->quaternion ? Blend::Slerp : Blend::Linear;
}

// Spherical interpolation of quaternions stored (real, i, j, k), along the shorter arc.
void slerp(const double* a, const double* b, double t, double* out) {
    double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    const double sign = dot < 0.0 ? -1.0 : 1.0;
    dot *= sign;
    double wa = 1.0 - t;
    double wb = t;
    // Nearly parallel: the sine below vanishes, and linear interpolation is exact enough.
    if (dot < 0.9995) {
        const double theta = std::acos(std::min(dot, 1.0));
        const double sinTheta = std::sin(theta);
        wa = std::sin((1.0 - t) * theta) / sinTheta;
        wb = std::sin(t * theta) / sinTheta;
    }
    double length = 0.0;
    for (int i = 0; i < 4; ++i) {
        out[i] = wa * a[i] + wb * sign * b[i];
        length += out[i] * out[i];
    }
    length = std::sqrt(length);
    if (length > 0.0)
        for (int i = 0; i < 4; ++i) out[i] /= length;
}

Value interpolate(const Value& lower, const Value& upper, double t) {
    const Blend blend = blendOf(lower);
    if (blend == Blend::Held || lower.numbers.size() != upper.numbers.size()) return lower;
    Value out = lower;
    std::vector<double>& numbers = out.numbers.edit();
    if (blend == Blend::Linear) {
        for (size_t i = 0; i < numbers.size(); ++i)
            numbers[i] = lower.numbers[i] + (upper.numbers[i] - lower.numbers[i]) * t;
        return out;
    }
    for (size_t i = 0; i + 4 <= numbers.size(); i += 4)
        slerp(&lower.numbers[i], &upper.numbers[i], t, &numbers[i]);
    return out;
}

std::optional<Value> unlessBlocked(const Value& value) {
    if (value.blocked) return std::nullopt;
    return value;
}

}  // namespace

std::optional<Value> Attribute::evaluate(double time) const {
    if (timeSamples.empty() && spline) {
        const std::optional<double> number = spline->evaluate(time);
        if (!number) return std::nullopt;
        Value value;
        value.typeName = spline->valueType;
        value.numbers.edit().push_back(*number);
        return value;
    }
    if (timeSamples.empty()) return defaultValue;
    const auto upper = timeSamples.lower_bound(time);
    if (upper == timeSamples.end()) return unlessBlocked(timeSamples.rbegin()->second);
    if (upper->first == time || upper == timeSamples.begin()) return unlessBlocked(upper->second);
    const auto lower = std::prev(upper);
    // A blocked sample holds no value until the next one; nothing is interpolated into a block.
    if (lower->second.blocked || upper->second.blocked) return unlessBlocked(lower->second);
    const double t = (time - lower->first) / (upper->first - lower->first);
    return interpolate(lower->second, upper->second, t);
}

}  // namespace obscura::usda
