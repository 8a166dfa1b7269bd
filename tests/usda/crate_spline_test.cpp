// Spline values of crate files (and relocates, the other value of crate 0.11 to 0.12): Ts's binary form (pxr/base/ts/binary.cpp, version 1) built here
// field by field as Ts_BinaryDataAccess::GetBinaryData writes it, decoded, and compared with the
// same spline written as text (`.spline = { ... }`), whose reading is tested against values worked
// out independently (spline_test.cpp); then malformed data, and splines in a whole crate file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "harness/usda/crate_file.h"
#include "harness/usda/crate_layer.h"
#include "harness/usda/crate_spline.h"
#include "tests/usda/crate_writer.h"
#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using crate::decodeSpline;
using crate::Failure;
using test::CrateWriter;

// The spline of attribute `x` of type `type` on </A> in a text layer holding just that.
Spline textSpline(const std::string& type, const std::string& body) {
    const auto stage = test::open("#usda 1.0\ndef \"A\"\n{\n    " + type + " x.spline = {\n" + body + "\n    }\n}\n");
    if (!stage || !stage->find("/A")->attribute("x")->spline) {
        ADD_FAILURE() << "no spline in:\n" << body;
        return {};
    }
    return *stage->find("/A")->attribute("x")->spline;
}

// GetBinaryData's output, one call per field it writes, in its order.
class TsBinary {
public:
    enum Value { Untyped = 0, Double = 1, Float = 2, Half = 3 };
    enum Extrapolation { None = 0, Held = 1, Linear = 2, Sloped = 3, LoopRepeat = 4, LoopReset = 5, LoopOscillate = 6 };
    enum Interpolation { Block = 0, HeldSegment = 1, LinearSegment = 2, Curve = 3 };

    TsBinary(Value type, bool hermite) : type_(type), hermite_(hermite) {}

    // Header byte 1 (version, value type, time-valued, curve type) and byte 2 (extrapolations,
    // whether inner loops are enabled).
    TsBinary& header(Extrapolation pre, Extrapolation post, bool loops, uint8_t version = 1) {
        put<uint8_t>(static_cast<uint8_t>(version | type_ << 4 | (hermite_ ? 0x80 : 0)));
        put<uint8_t>(static_cast<uint8_t>(pre | post << 3 | (loops ? 0x40 : 0)));
        return *this;
    }
    TsBinary& slope(double s) { return put<double>(s); }  // each Sloped extrapolation's, pre first
    TsBinary& loop(double protoStart, double protoEnd, int32_t pre, int32_t post, double valueOffset) {
        return put(protoStart).put(protoEnd).put(pre).put(post).put(valueOffset);
    }
    TsBinary& knotCount(uint32_t count) { return put(count); }
    // Flag byte (dual-valued, next interpolation, curve type, Maya forms), time, value, pre-value
    // if dual-valued, widths unless Hermite, then slopes (Maya heights in Maya form).
    struct Knot {
        double time, value;
        std::optional<double> preValue;
        Interpolation next = HeldSegment;
        double preWidth = 0, postWidth = 0, preSlope = 0, postSlope = 0;
        bool preMaya = false, postMaya = false;
    };
    TsBinary& knot(const Knot& k) {
        put<uint8_t>(static_cast<uint8_t>((k.preValue ? 1 : 0) | k.next << 1 | (hermite_ ? 0x08 : 0) |
                                          (k.preMaya ? 0x10 : 0) | (k.postMaya ? 0x20 : 0)));
        put(k.time);
        value(k.value);
        if (k.preValue) value(*k.preValue);
        if (!hermite_) put(k.preWidth).put(k.postWidth);
        value(k.preSlope);
        value(k.postSlope);
        return *this;
    }
    TsBinary& raw(const std::string& bytes) {
        bytes_ += bytes;
        return *this;
    }
    // As crateFile.cpp stores it (Read<TsSpline>): a uint64 byte count, then the bytes.
    std::string sized() const {
        const uint64_t size = bytes_.size();
        return std::string(reinterpret_cast<const char*>(&size), 8) + bytes_;
    }

private:
    template <class T>
    TsBinary& put(T v) {
        bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
        return *this;
    }
    void value(double v) {
        if (type_ == Float) put(static_cast<float>(v));
        else if (type_ == Half) put(halfBits(v));
        else put(v);
    }
    // Exact for the small values used here: 1.0 = 0x3C00 scaled by powers of two and halves.
    static uint16_t halfBits(double v) {
        if (v == 0.0) return 0;
        int exponent = 0;
        const double mantissa = std::frexp(std::fabs(v), &exponent);  // [0.5, 1)
        const auto bits = static_cast<uint16_t>((exponent + 14) << 10 | static_cast<int>((mantissa * 2 - 1) * 1024));
        return static_cast<uint16_t>(v < 0 ? bits | 0x8000 : bits);
    }

    Value type_;
    bool hermite_;
    std::string bytes_;
};

std::shared_ptr<const Spline> decoded(const TsBinary& binary, const std::string& type = "double") {
    const std::string bytes = "pad" + binary.sized();
    return decodeSpline(bytes, 3, type);
}

std::string failure(const TsBinary& binary) {
    try {
        decoded(binary);
    } catch (const Failure& f) {
        return "byte " + std::to_string(f.offset) + ": " + f.message;
    }
    return "no failure";
}

TEST(CrateSplines, BezierWithLoopsDualValuesAndMayaTangentsReadsAsItsText) {
    TsBinary binary(TsBinary::Double, false);
    binary.header(TsBinary::Held, TsBinary::Sloped, true)
        .slope(0.5)
        .loop(0, 10, 1, 2, 3)
        .knotCount(3)
        .knot({.time = 0, .value = 2, .preValue = 1, .next = TsBinary::Curve, .postWidth = 3, .postSlope = 2})
        .knot({.time = 10, .value = 5, .next = TsBinary::Curve, .preWidth = 4, .postWidth = 6, .preSlope = -1,
               .postSlope = 1.5, .postMaya = true})
        .knot({.time = 20, .value = 7, .next = TsBinary::LinearSegment, .preWidth = 1, .preSlope = 0});
    const Spline text = textSpline("double",
                                   "bezier,\npre: held,\npost: sloped(0.5),\nloop: (0, 10, 1, 2, 3),\n"
                                   "0: 1 & 2; post curve ws(3, 2),\n10: 5; pre ws(4, -1); post curve wh(6, 1.5),\n"
                                   "20: 7; pre ws(1, 0); post linear");
    EXPECT_EQ(*decoded(binary), text);
    EXPECT_DOUBLE_EQ(text.knots[1].postSlope, 0.25);  // Maya height over Maya width
}

TEST(CrateSplines, HermiteFloatSplineTakesMayaHeightsOverItsSegments) {
    TsBinary binary(TsBinary::Float, true);
    binary.header(TsBinary::Linear, TsBinary::LoopOscillate, false)
        .knotCount(3)
        .knot({.time = 0, .value = 1, .next = TsBinary::Curve, .postSlope = 2, .postMaya = true})
        .knot({.time = 4, .value = 3, .next = TsBinary::Curve, .preSlope = 1, .postSlope = 0.5, .preMaya = true})
        .knot({.time = 6, .value = -2, .next = TsBinary::Block, .preSlope = 0.25});
    const Spline text = textSpline("float",
                                   "hermite,\npre: linear,\npost: loop oscillate,\n0: 1; post curve h(2),\n"
                                   "4: 3; pre h(1); post curve s(0.5),\n6: -2; pre s(0.25); post none");
    EXPECT_EQ(*decoded(binary, "float"), text);
    EXPECT_DOUBLE_EQ(text.knots[1].preSlope, -0.25);  // -height over the segment's length
}

TEST(CrateSplines, HalfValuesAndUntypedEmptySplines) {
    TsBinary half(TsBinary::Half, false);
    half.header(TsBinary::None, TsBinary::Held, false)
        .knotCount(2)
        .knot({.time = 1, .value = -0.75, .next = TsBinary::LinearSegment})
        .knot({.time = 3, .value = 1.5});
    EXPECT_EQ(*decoded(half, "half"), textSpline("half", "pre: none,\npost: held,\n1: -0.75; post linear,\n3: 1.5"));

    // A spline that never had knots: no value type and no knot count (GetBinaryData writes none).
    TsBinary untyped(TsBinary::Untyped, false);
    untyped.header(TsBinary::Held, TsBinary::Held, false);
    const auto empty = decoded(untyped);
    EXPECT_TRUE(empty->knots.empty());
    EXPECT_FALSE(empty->evaluate(0));
}

TEST(CrateSplines, MalformedDataFailsAtItsByte) {
    // Byte 3 holds the size, byte 11 the first header byte, byte 13 the knot count, byte 17 the
    // first knot (49 bytes for a Bezier double knot).
    TsBinary future(TsBinary::Double, false);
    future.header(TsBinary::Held, TsBinary::Held, false, 2).knotCount(0);
    EXPECT_EQ(failure(future), "byte 11: spline data of version 2 (reads version 1)");

    TsBinary truncated(TsBinary::Double, false);
    truncated.header(TsBinary::Held, TsBinary::Held, false).knotCount(1).raw(std::string(20, '\0'));
    EXPECT_EQ(failure(truncated), "byte 13: spline of 1 knots cannot fit in its 26 bytes");

    // Room for the smallest Hermite knot (33 bytes), not for this dual-valued one (41).
    TsBinary shortKnot(TsBinary::Double, true);
    shortKnot.header(TsBinary::Held, TsBinary::Held, false).knotCount(1).raw('\x01' + std::string(32, '\0'));
    EXPECT_NE(failure(shortKnot).find("runs past the end"), std::string::npos) << failure(shortKnot);

    TsBinary badMode(TsBinary::Double, false);
    badMode.header(TsBinary::Held, static_cast<TsBinary::Extrapolation>(7), false).knotCount(0);
    EXPECT_EQ(failure(badMode), "byte 12: unknown spline extrapolation mode 7");

    TsBinary unordered(TsBinary::Double, false);
    unordered.header(TsBinary::Held, TsBinary::Held, false).knotCount(2).knot({.time = 5, .value = 0}).knot({.time = 1, .value = 0});
    EXPECT_EQ(failure(unordered), "byte 66: spline knot at time 1.000000 does not follow the one before");

    TsBinary trailing(TsBinary::Double, false);
    trailing.header(TsBinary::Held, TsBinary::Held, false).knotCount(0).raw("x");
    EXPECT_EQ(failure(trailing), "byte 17: 1 bytes follow the spline's knots");

    // The size itself runs past the data.
    std::string cut = "pad" + trailing.sized();
    cut.resize(cut.size() - 2);
    EXPECT_THROW(decodeSpline(cut, 3, "double"), Failure);
}

// ---- Splines in a crate file ---------------------------------------------------------------------

TEST(CrateSplines, ASplineFieldAnimatesItsAttribute) {
    TsBinary binary(TsBinary::Double, false);
    binary.header(TsBinary::Held, TsBinary::Linear, false)
        .knotCount(2)
        .knot({.time = 0, .value = 1, .next = TsBinary::LinearSegment})
        .knot({.time = 10, .value = 21});
    CrateWriter writer;
    const uint64_t spline = writer.stored(crate::Type::Spline, binary.sized());
    const uint64_t type = CrateWriter::inlined(crate::Type::Token, writer.token("double"));
    const float seven = 7.0f;
    uint32_t sevenBits = 0;
    std::memcpy(&sevenBits, &seven, 4);
    const std::string bytes = writer.write(
        {{"x", {{"typeName", type}, {"default", CrateWriter::inlined(crate::Type::Double, sevenBits)}, {"spline", spline}}}});
    const auto stage = test::open(bytes, "splines.usdc");
    ASSERT_TRUE(stage);
    const Attribute* x = stage->find("/A")->attribute("x");
    ASSERT_TRUE(x && x->spline);
    EXPECT_EQ(*x->spline, textSpline("double", "pre: held,\npost: linear,\n0: 1; post linear,\n10: 21"));
    EXPECT_EQ(x->evaluate(5)->numbers[0], 11.0);  // the spline before the default
    EXPECT_EQ(x->evaluate(20)->numbers[0], 41.0);
}

TEST(CrateSplines, AMalformedSplineSkipsOnlyThatSpline) {
    TsBinary good(TsBinary::Double, false);
    good.header(TsBinary::Held, TsBinary::Held, false).knotCount(1).knot({.time = 0, .value = 3});
    TsBinary future(TsBinary::Double, false);
    future.header(TsBinary::Held, TsBinary::Held, false, 2).knotCount(0);
    CrateWriter writer;
    const uint64_t goodRep = writer.stored(crate::Type::Spline, good.sized());
    const uint64_t futureRep = writer.stored(crate::Type::Spline, future.sized());
    const uint64_t type = CrateWriter::inlined(crate::Type::Token, writer.token("double"));
    const uint64_t vectorType = CrateWriter::inlined(crate::Type::Token, writer.token("float3"));
    const std::string bytes = writer.write({
        {"bad", {{"typeName", type}, {"default", CrateWriter::inlined(crate::Type::Double, 0)}, {"spline", futureRep}}},
        {"good", {{"typeName", type}, {"spline", goodRep}}},
        {"vector", {{"typeName", vectorType}, {"spline", goodRep}}},
    });
    const auto stage = test::open(bytes, "splines.usdc");
    ASSERT_TRUE(stage);
    const Prim& prim = *stage->find("/A");
    EXPECT_FALSE(prim.attribute("bad")->spline);
    EXPECT_EQ(prim.attribute("bad")->evaluate(5)->numbers[0], 0.0);  // its default stays
    ASSERT_TRUE(prim.attribute("good")->spline);
    EXPECT_EQ(prim.attribute("good")->evaluate(5)->numbers[0], 3.0);
    EXPECT_FALSE(prim.attribute("vector")->spline);
    std::vector<std::string> messages;
    for (const Warning& warning : stage->warnings()) messages.push_back(warning.where.file + ": " + warning.message);
    const uint64_t versionByte = (futureRep & ((uint64_t(1) << 48) - 1)) + 8;
    EXPECT_NE(std::find(messages.begin(), messages.end(),
                        "splines.usdc: </A.bad>: byte " + std::to_string(versionByte) +
                            ": malformed spline (spline data of version 2 (reads version 1)); the attribute's spline "
                            "is skipped"),
              messages.end())
        << ::testing::PrintToString(messages);
}

// An inner loop of two billion iterations would unroll past kMaxUnrolledSplineKnots: reported and
// left out, as in text, the default kept.
TEST(CrateSplines, AnUnboundedInnerLoopIsLeftOut) {
    TsBinary binary(TsBinary::Double, false);
    binary.header(TsBinary::Held, TsBinary::Held, true)
        .loop(0, 10, 0, 2000000000, 1)
        .knotCount(2)
        .knot({.time = 0, .value = 0, .next = TsBinary::LinearSegment})
        .knot({.time = 5, .value = 1});
    CrateWriter writer;
    const uint64_t spline = writer.stored(crate::Type::Spline, binary.sized());
    const uint64_t type = CrateWriter::inlined(crate::Type::Token, writer.token("double"));
    const std::string bytes =
        writer.write({{"x", {{"typeName", type}, {"default", CrateWriter::inlined(crate::Type::Double, 0)}, {"spline", spline}}}});
    const auto stage = test::open(bytes, "splines.usdc");
    ASSERT_TRUE(stage);
    EXPECT_FALSE(stage->find("/A")->attribute("x")->spline);
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_EQ(stage->warnings()[0].message,
              "</A.x>: a spline that is left out: its inner loop repeats 2 knots 2000000001 times, more than the 10000 "
              "knots a spline may unroll; its default and time samples are used");
}

// Layer relocates (crate 0.11.0): a count, then source and target path indexes in pairs, read as
// the text reader keeps `relocates` layer metadata.
TEST(CrateRelocates, LayerRelocatesReadAsTheTextReaderKeepsThem) {
    CrateWriter writer;
    std::string pairs = std::string("\1\0\0\0\0\0\0\0", 8);
    for (uint32_t path : {1u, 2u}) pairs += std::string(reinterpret_cast<const char*>(&path), 4);
    const uint64_t relocates = writer.stored(crate::Type::Relocates, pairs);
    const uint64_t type = CrateWriter::inlined(crate::Type::Token, writer.token("double"));
    const std::string bytes = writer.write({{"x", {{"typeName", type}}}}, {{"layerRelocates", relocates}});
    const auto layer = readCrateLayer(bytes, "relocates.usdc");
    ASSERT_TRUE(layer->metadata.count("relocates"));
    EXPECT_EQ(layer->metadata.at("relocates").strings.vector(), (std::vector<std::string>{"/A", "/A.x"}));
}

}  // namespace
}  // namespace obscura::usda
