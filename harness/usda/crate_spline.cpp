// Ts's binary spline form, version 1 (pxr/base/ts/binary.cpp, GetBinaryData and _ParseV1):
//   header byte 1: version (bits 0-3), value type (4-5: 0 none, 1 double, 2 float, 3 half),
//                  time-valued (6), curve type (7: Hermite)
//   header byte 2: pre-extrapolation (bits 0-2), post-extrapolation (3-5), inner loop (6)
//   a double slope for each Sloped extrapolation, pre first
//   the inner loop: protoStart, protoEnd (double), numPreLoops, numPostLoops (int32), valueOffset (double)
//   with a value type: a uint32 knot count, then per knot a flag byte (dual-valued (bit 0), next
//   interpolation (1-2), curve type (3, per knot and unused), tangents in Maya form (4 pre, 5 post)),
//   the time (double), the value, the pre-value if dual-valued, the tangent widths (double, Bezier
//   only) and the tangent slopes (Maya heights when in Maya form), values and slopes in the value type.
#include "harness/usda/crate_spline.h"

#include <optional>
#include <vector>

#include "harness/usda/crate_values.h"

namespace obscura::usda::crate {

namespace {

constexpr uint8_t kBinaryVersion = 1;

// A knot's tangent in Maya form holds its height; a Hermite's slope waits for its neighbours.
struct MayaHeights {
    std::optional<double> pre, post;
};

SplineExtrapolation extrapolation(uint8_t mode, ByteReader& reader, uint64_t at) {
    using Mode = SplineExtrapolationMode;
    switch (mode) {
    case 0: return {Mode::None};
    case 1: return {Mode::Held};
    case 2: return {Mode::Linear};
    case 3: return {Mode::Sloped, reader.read<double>()};
    case 4: return {Mode::LoopRepeat};
    case 5: return {Mode::LoopReset};
    case 6: return {Mode::LoopOscillate};
    default: throw Failure{at, "unknown spline extrapolation mode " + std::to_string(mode)};
    }
}

}  // namespace

std::shared_ptr<const Spline> decodeSpline(std::span<const char> bytes, uint64_t at, const std::string& valueType) {
    ByteReader sized(bytes, at);
    const uint64_t size = sized.read<uint64_t>();
    const uint64_t start = sized.tell();
    ByteReader reader(bytes.first(start + sized.take(size).size()), start);
    auto spline = std::make_shared<Spline>();
    spline->valueType = valueType;
    if (size == 0) return spline;  // a spline without knots

    const auto header = reader.read<uint8_t>();
    if ((header & 0x0F) != kBinaryVersion)
        throw Failure{start, "spline data of version " + std::to_string(header & 0x0F) + " (reads version " +
                                 std::to_string(kBinaryVersion) + ")"};
    const int valueKind = (header >> 4) & 0x03;
    spline->hermite = header & 0x80;
    const uint64_t extrapolationsAt = reader.tell();
    const auto extrapolations = reader.read<uint8_t>();
    // binary.cpp writes three bits per mode; its v1 reader masks the post mode to two (0x18),
    // which would lose the looping modes, so the writer's layout is read.
    spline->pre = extrapolation(extrapolations & 0x07, reader, extrapolationsAt);
    spline->post = extrapolation((extrapolations >> 3) & 0x07, reader, extrapolationsAt);
    if (extrapolations & 0x40) {
        SplineLoop loop;
        loop.protoStart = reader.read<double>();
        loop.protoEnd = reader.read<double>();
        loop.numPreLoops = reader.read<int32_t>();
        loop.numPostLoops = reader.read<int32_t>();
        loop.valueOffset = reader.read<double>();
        spline->loop = loop;
    }
    // Untyped data (a spline that never had knots) ends here; Ts reads any knots of it as double.
    if (valueKind == 0 && reader.tell() == reader.size()) return spline;

    const size_t valueBytes = valueKind == 2 ? 4 : valueKind == 3 ? 2 : 8;
    auto value = [&] {
        if (valueBytes == 4) return double(reader.read<float>());
        if (valueBytes == 2) return halfToDouble(reader.read<uint16_t>());
        return reader.read<double>();
    };
    const uint64_t countAt = reader.tell();
    const auto count = reader.read<uint32_t>();
    const uint64_t smallestKnot = 1 + 8 + 3 * valueBytes + (spline->hermite ? 0 : 16);
    if (count > (reader.size() - reader.tell()) / smallestKnot)
        throw Failure{countAt, "spline of " + std::to_string(count) + " knots cannot fit in its " +
                                   std::to_string(size) + " bytes"};
    std::vector<MayaHeights> heights(count);
    spline->knots.resize(count);
    for (uint32_t i = 0; i < count; ++i) {
        const uint64_t knotAt = reader.tell();
        SplineKnot& knot = spline->knots[i];
        const auto flags = reader.read<uint8_t>();
        knot.next = static_cast<SplineInterpolation>((flags >> 1) & 0x03);  // TsInterpMode's order
        knot.time = reader.read<double>();
        if (i > 0 && !(knot.time > spline->knots[i - 1].time))
            throw Failure{knotAt, "spline knot at time " + std::to_string(knot.time) + " does not follow the one before"};
        knot.value = value();
        if (flags & 0x01) knot.preValue = value();
        double preMayaWidth = 0.0, postMayaWidth = 0.0;
        if (!spline->hermite) {
            knot.preWidth = preMayaWidth = reader.read<double>();
            knot.postWidth = postMayaWidth = reader.read<double>();
        }
        knot.preSlope = value();
        knot.postSlope = value();
        if (flags & 0x10) {
            knot.preWidth /= 3.0;
            heights[i].pre = knot.preSlope;
            knot.preSlope = slopeOfMayaTangent(true, knot.preSlope, preMayaWidth);
        }
        if (flags & 0x20) {
            knot.postWidth /= 3.0;
            heights[i].post = knot.postSlope;
            knot.postSlope = slopeOfMayaTangent(false, knot.postSlope, postMayaWidth);
        }
    }
    if (spline->hermite) {
        std::vector<SplineKnot>& knots = spline->knots;
        for (size_t i = 0; i < knots.size(); ++i) {
            if (heights[i].pre && i > 0)
                knots[i].preSlope = slopeOfMayaTangent(true, *heights[i].pre, knots[i].time - knots[i - 1].time);
            if (heights[i].post && i + 1 < knots.size())
                knots[i].postSlope = slopeOfMayaTangent(false, *heights[i].post, knots[i + 1].time - knots[i].time);
        }
    }
    if (reader.tell() != reader.size())
        throw Failure{reader.tell(), std::to_string(reader.size() - reader.tell()) + " bytes follow the spline's knots"};
    return spline;
}

}  // namespace obscura::usda::crate
