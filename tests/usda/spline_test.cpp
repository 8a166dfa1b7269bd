// Spline-valued attributes (OpenUSD 25.05's TsSpline) read from .usda text: each segment kind and
// extrapolation against values worked out independently, loops, dual values, value resolution
// against time samples and defaults, and the sample times motion blur reads.
#include <cmath>
#include <functional>

#include "tests/usda/usda_test_util.h"

namespace obscura::usda {
namespace {

using test::open;

// The spline of attribute `x` on </A> in a layer holding just that.
Spline splineOf(const std::string& body) {
    const auto stage = open("#usda 1.0\ndef \"A\"\n{\n    double x.spline = {\n" + body + "\n    }\n}\n");
    if (!stage || !stage->find("/A")->attribute("x")->spline) {
        ADD_FAILURE() << "no spline in:\n" << body;
        return {};
    }
    return *stage->find("/A")->attribute("x")->spline;
}

double valueAt(const Spline& spline, double time) {
    const std::optional<double> value = spline.evaluate(time);
    if (!value) ADD_FAILURE() << "no value at " << time;
    return value.value_or(NAN);
}

double cubicBezier(double p0, double p1, double p2, double p3, double u) {
    const double v = 1.0 - u;
    return v * v * v * p0 + 3 * v * v * u * p1 + 3 * v * u * u * p2 + u * u * u * p3;
}

// u in [0, 1] with f(u) = target, f increasing, by bisection.
double solveIncreasing(const std::function<double(double)>& f, double target) {
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 200; ++i) (f(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
}

TEST(Splines, LinearSegmentMidpointAndHeldSegment) {
    const Spline spline = splineOf("0: 2; post linear,\n10: 22; post held,\n20: -4");
    EXPECT_DOUBLE_EQ(valueAt(spline, 5), 12.0);
    EXPECT_DOUBLE_EQ(valueAt(spline, 10), 22.0);
    EXPECT_DOUBLE_EQ(valueAt(spline, 19.999), 22.0);  // held until the next knot
    EXPECT_DOUBLE_EQ(valueAt(spline, 20), -4.0);
}

// x(u) and y(u) are cubic Beziers through the knots and the tangents' ends: the post-tangent
// reaches (t0 + w, v0 + w * slope), the pre-tangent (t1 - w, v1 - w * slope).
TEST(Splines, BezierSegmentIsTheTimeParametrisedCubic) {
    const Spline spline = splineOf("bezier,\n0: 1; post curve ws(3, 2),\n10: 5; pre ws(4, -1); post held");
    for (double time : {0.5, 2.5, 5.0, 7.0, 9.9}) {
        const double u = solveIncreasing([](double v) { return cubicBezier(0, 3, 10 - 4, 10, v); }, time);
        EXPECT_NEAR(valueAt(spline, time), cubicBezier(1, 1 + 3 * 2, 5 - 4 * -1, 5, u), 1e-9) << time;
    }
}

// Tangents reaching past each other would make time run backwards; both shrink in proportion
// until it just does not (Ts's Keep Ratio): (6, 6) on a segment of 4 become (4, 4), where x'(1/2) = 0.
TEST(Splines, RegressiveBezierTangentsShrinkInProportion) {
    const Spline spline = splineOf("bezier,\n0: 0; post curve ws(6, 1),\n4: 4; pre ws(6, 1)");
    for (double time : {0.5, 2.0, 3.5}) {
        const double u = solveIncreasing([](double v) { return cubicBezier(0, 4, 0, 4, v); }, time);
        EXPECT_NEAR(valueAt(spline, time), cubicBezier(0, 4, 0, 4, u), 1e-6) << time;
    }
}

TEST(Splines, HermiteSegmentTakesSlopesOnly) {
    const Spline spline = splineOf("hermite,\n2: 1; post curve s(2),\n6: 3; pre s(-1)");
    for (double time : {2.5, 4.0, 5.5}) {
        const double u = (time - 2) / 4, m0 = 2 * 4, m1 = -1 * 4;
        const double expected = (2 * u * u * u - 3 * u * u + 1) * 1 + (u * u * u - 2 * u * u + u) * m0 +
                                (-2 * u * u * u + 3 * u * u) * 3 + (u * u * u - u * u) * m1;
        EXPECT_NEAR(valueAt(spline, time), expected, 1e-12) << time;
    }
}

// Maya's tangent form: width three times Ts's and a height (slope * width), negated before a knot.
TEST(Splines, MayaFormTangentsAreStandardOnes) {
    const Spline maya = splineOf("bezier,\n0: 1; post curve wh(9, 18),\n10: 5; pre wh(12, 12)");
    const Spline standard = splineOf("bezier,\n0: 1; post curve ws(3, 2),\n10: 5; pre ws(4, -1)");
    for (double time : {2.5, 7.0}) EXPECT_NEAR(valueAt(maya, time), valueAt(standard, time), 1e-12);
}

TEST(Splines, DualValuedKnotJumpsAtItsTime) {
    const Spline spline = splineOf("0: 0; post linear,\n10: 4 & 8; post linear,\n20: 18");
    EXPECT_DOUBLE_EQ(valueAt(spline, 5), 2.0);
    EXPECT_NEAR(valueAt(spline, 10 - 1e-9), 4.0, 1e-8);
    EXPECT_DOUBLE_EQ(valueAt(spline, 10), 8.0);
    EXPECT_DOUBLE_EQ(valueAt(spline, 15), 13.0);
}

TEST(Splines, SegmentOfModeNoneHasNoValue) {
    const Spline spline = splineOf("0: 1; post none,\n10: 3");
    EXPECT_FALSE(spline.evaluate(5));
    EXPECT_FALSE(spline.evaluate(0));
    EXPECT_DOUBLE_EQ(valueAt(spline, 10), 3.0);
}

TEST(Splines, ExtrapolationModes) {
    const std::string knots = "0: 1; post linear,\n10: 6; post held";
    EXPECT_DOUBLE_EQ(valueAt(splineOf(knots), -5), 1.0);  // held by default
    EXPECT_DOUBLE_EQ(valueAt(splineOf(knots), 15), 6.0);
    EXPECT_FALSE(splineOf("pre: none,\npost: none,\n" + knots).evaluate(-5));
    EXPECT_FALSE(splineOf("pre: none,\npost: none,\n" + knots).evaluate(15));
    // Linear continues the end segments (the last knot's own held interpolation faces nothing).
    EXPECT_DOUBLE_EQ(valueAt(splineOf("pre: linear,\npost: linear,\n" + knots), -4), -1.0);
    EXPECT_DOUBLE_EQ(valueAt(splineOf("pre: linear,\npost: linear,\n" + knots), 20), 11.0);
    EXPECT_DOUBLE_EQ(valueAt(splineOf("pre: sloped(2),\npost: sloped(-0.5),\n" + knots), -1), -1.0);
    EXPECT_DOUBLE_EQ(valueAt(splineOf("pre: sloped(2),\npost: sloped(-0.5),\n" + knots), 14), 4.0);
    // Linear beside a curve continues the knot's tangent.
    EXPECT_DOUBLE_EQ(valueAt(splineOf("post: linear,\n0: 0; post curve ws(1, 1),\n10: 5; pre ws(1, 3)"), 12), 11.0);
}

TEST(Splines, ExtrapolatingLoops) {
    const std::string knots = "0: 0; post linear,\n10: 10; post held";
    const Spline repeat = splineOf("pre: loop repeat,\npost: loop repeat,\n" + knots);
    EXPECT_DOUBLE_EQ(valueAt(repeat, 12), 12.0);
    EXPECT_DOUBLE_EQ(valueAt(repeat, 25), 25.0);
    EXPECT_DOUBLE_EQ(valueAt(repeat, -5), -5.0);
    const Spline reset = splineOf("pre: loop reset,\npost: loop reset,\n" + knots);
    EXPECT_DOUBLE_EQ(valueAt(reset, 12), 2.0);
    EXPECT_DOUBLE_EQ(valueAt(reset, 20), 0.0);  // each iteration starts again at its first knot
    EXPECT_DOUBLE_EQ(valueAt(reset, -3), 7.0);
    const Spline oscillate = splineOf("pre: loop oscillate,\npost: loop oscillate,\n" + knots);
    EXPECT_DOUBLE_EQ(valueAt(oscillate, 12), 8.0);  // the first iteration after runs backwards
    EXPECT_DOUBLE_EQ(valueAt(oscillate, 23), 3.0);  // the second forwards again
    EXPECT_DOUBLE_EQ(valueAt(oscillate, -3), 3.0);
}

// loop: (protoStart, protoEnd, before, after, valueOffset): the knots in [0, 10) repeat once before
// and once after, each copy 100 higher; the last iteration closes on a copy of the first knot, and
// the knot authored at 10 lies inside the looped interval, so it is shadowed.
TEST(Splines, InnerLoopRepeatsThePrototype) {
    const Spline spline = splineOf("loop: (0, 10, 1, 1, 100),\n-20: -500; post linear,\n0: 0; post linear,\n"
                                   "5: 10; post linear,\n10: 1000; post linear,\n30: 300");
    EXPECT_DOUBLE_EQ(valueAt(spline, 2.5), 5.0);
    EXPECT_DOUBLE_EQ(valueAt(spline, 7.5), 55.0);  // toward the copy of the first knot at 10
    EXPECT_DOUBLE_EQ(valueAt(spline, 12.5), 105.0);
    EXPECT_DOUBLE_EQ(valueAt(spline, 17.5), 155.0);
    EXPECT_DOUBLE_EQ(valueAt(spline, -7.5), -95.0);
    EXPECT_DOUBLE_EQ(valueAt(spline, -15), -300.0);  // from the authored knot to the first copy
    EXPECT_DOUBLE_EQ(valueAt(spline, 25), 250.0);   // from the closing copy to the authored knot
}

// A spline this reader cannot read, in a balanced block, loses its attribute only the spline: the
// file opens, the default shows, and one warning at the spline names where the problem lies.
TEST(Splines, UnreadableSplinesAreLeftOutWhereTheyLie) {
    const struct {
        const char* body;
        const char* problem;
    } cases[] = {
        {"        pre: bouncy,\n        1: 2",
         "test.usda:5:14: expected an extrapolation (none, held, linear, sloped(slope) or loop repeat|reset|oscillate), "
         "found 'bouncy'"},
        {"        1: 2; post linear\n        3: 4", "test.usda:6:9: expected ',' or '}' after a spline item, found '3'"},
        {"        loop: (0, 10, 1, 2.5, 0),\n        0: 1",
         "test.usda:5:26: expected a whole number for the loop's count after in the spline, found '2.5'"},
        {"        loop: (0, 10, 1e12, 2, 0),\n        0: 1",
         "test.usda:5:23: expected a whole number for the loop's count before in the spline, found '1e12'"},
    };
    for (const auto& [body, problem] : cases) {
        const auto stage = open(std::string("#usda 1.0\ndef \"A\"\n{\n    double x.spline = {\n") + body +
                                "\n    }\n    double x = 7\n}\n");
        ASSERT_TRUE(stage) << problem;
        const Attribute* x = stage->find("/A")->attribute("x");
        EXPECT_FALSE(x->spline) << problem;
        EXPECT_DOUBLE_EQ(x->evaluate(3.0)->numbers[0], 7.0) << problem;
        ASSERT_EQ(stage->warnings().size(), 1u) << problem;
        EXPECT_EQ(stage->warnings()[0].where.line, 4) << problem;
        EXPECT_EQ(stage->warnings()[0].message, std::string("attribute 'x' of </A> has a spline that cannot be read (") +
                                                    problem + "); its default and time samples are used");
    }
}

// What a file cannot make a spline cost: an inner loop that would unroll past
// kMaxUnrolledSplineKnots is reported where authored and left out (the default shows), and an
// interval holding millions of repetitions of a looping extrapolation is sampled evenly.
TEST(Splines, UnboundedLoopsAreBounded) {
    const auto stage = open("#usda 1.0\ndef \"A\"\n{\n    double x = 7\n    double x.spline = {\n"
                            "        loop: (0, 10, 0, 2000000000, 1),\n        0: 0; post linear,\n        5: 1\n    }\n}\n");
    ASSERT_TRUE(stage);
    const Attribute* x = stage->find("/A")->attribute("x");
    EXPECT_FALSE(x->spline);
    EXPECT_DOUBLE_EQ(x->evaluate(3.0)->numbers[0], 7.0);
    ASSERT_EQ(stage->warnings().size(), 1u);
    EXPECT_EQ(stage->warnings()[0].where.line, 5);
    EXPECT_NE(stage->warnings()[0].message.find("repeats 2 knots 2000000001 times"), std::string::npos)
        << stage->warnings()[0].message;

    const Spline tiny = splineOf("post: loop repeat,\n0: 0; post linear,\n0.000001: 1");
    const std::vector<double> times = tiny.sampleTimes(0.0, 1000.0);
    EXPECT_EQ(times.size(), kMaxSplineSampleTimes);
    EXPECT_DOUBLE_EQ(times.front(), 0.0);
    EXPECT_DOUBLE_EQ(times.back(), 1000.0);
}

// Value resolution (UsdResolveInfo): the strongest opinion with a value wins, within one its
// time samples, then its spline, then its default; AnimationBlock hides weaker splines but not
// its own layer's. A reference (with its layer offset) carries the weaker opinions.
TEST(Splines, ResolveAgainstTimeSamplesAndDefaults) {
    const auto stage = open(R"(#usda 1.0
def "Weak"
{
    double samplesWin = 1
    double samplesWin.spline = { 0: 10; post linear, 10: 20 }
    double samplesWin.timeSamples = { 0: 100, 10: 200 }
    double splineOverDefault = 1
    double splineOverDefault.spline = { 0: 10; post linear, 10: 20 }
    double strongerDefault.spline = { 0: 10; post linear, 10: 20 }
    double blocked = 3
    double blocked.spline = { 0: 10; post linear, 10: 20 }
    double ownBlock = AnimationBlock
    double ownBlock.spline = { 0: 10; post linear, 10: 20 }
    double shifted.spline = { 0: 10; post curve ws(2, 1), 10: 20; pre ws(2, 1) }
}
def "A" (
    references = </Weak> (offset = 5; scale = 2)
)
{
    double strongerDefault = 7
    double blocked = AnimationBlock
}
)");
    ASSERT_TRUE(stage);
    const Prim& a = *stage->find("/A");
    auto at = [&](const char* name, double time) { return a.attribute(name)->evaluate(time)->numbers.at(0); };
    EXPECT_DOUBLE_EQ(at("samplesWin", 15), 150.0);
    EXPECT_DOUBLE_EQ(at("splineOverDefault", 15), 15.0);  // stage 15 is the reference's 5
    EXPECT_DOUBLE_EQ(a.attribute("splineOverDefault")->defaultValue->numbers.at(0), 1.0);
    EXPECT_DOUBLE_EQ(at("strongerDefault", 15), 7.0);
    EXPECT_DOUBLE_EQ(at("blocked", 15), 3.0);
    EXPECT_DOUBLE_EQ(at("ownBlock", 15), 15.0);
    EXPECT_FALSE(a.attribute("ownBlock")->defaultValue);
    EXPECT_EQ(a.attribute("ownBlock")->evaluate(15)->typeName, "double");
    // Retimed by the offset, the curve's shape in stage time is the authored one stretched.
    const Spline authored = *stage->find("/Weak")->attribute("shifted")->spline;
    for (double time : {1.0, 4.5, 8.0}) EXPECT_NEAR(at("shifted", 5 + 2 * time), valueAt(authored, time), 1e-12);
}

// A spline on an xformOp moves the prim: it is animated, and the times motion blur samples within
// a shutter include steps along the curve and, past the knots, its looping copies.
TEST(Splines, AnimateTransformsAndOfferSampleTimes) {
    const auto stage = open(R"(#usda 1.0
def Xform "Spin"
{
    double xformOp:rotateZ.spline = {
        bezier,
        post: loop repeat,
        0: 0; post curve ws(1, 90),
        4: 360; pre ws(1, 90),
    }
    uniform token[] xformOpOrder = ["xformOp:rotateZ"]
}
)");
    ASSERT_TRUE(stage);
    const Prim& spin = *stage->find("/Spin");
    EXPECT_TRUE(spin.attribute("xformOp:rotateZ")->isAnimated());
    EXPECT_EQ(stage->transformSampleTimes(spin), (std::vector<double>{0, 1, 2, 3, 4}));
    EXPECT_EQ(stage->transformSampleTimes(spin, 0.5, 2.5), (std::vector<double>{1, 2}));
    EXPECT_EQ(stage->transformSampleTimes(spin, 8.5, 9.5), (std::vector<double>{9}));
    const auto m = stage->localTransform(spin, 6.0);  // 360 + 180 degrees: a half turn
    EXPECT_NEAR(m[0], -1.0, 1e-9);
    EXPECT_NEAR(m[5], -1.0, 1e-9);
}

TEST(Splines, SceneFileAnimatesAScale) {
    const auto stage = test::openFile(test::kDataDir + "/spline_scale.usda");
    ASSERT_TRUE(stage);
    const Prim& ball = *stage->find("/Ball");
    EXPECT_TRUE(stage->warnings().empty());
    EXPECT_DOUBLE_EQ(ball.attribute("radius")->evaluate(0)->numbers.at(0), 1.0);
    EXPECT_DOUBLE_EQ(ball.attribute("radius")->evaluate(12)->numbers.at(0), 2.0);
    EXPECT_DOUBLE_EQ(ball.attribute("radius")->evaluate(30)->numbers.at(0), 2.0);
}

}  // namespace
}  // namespace obscura::usda
