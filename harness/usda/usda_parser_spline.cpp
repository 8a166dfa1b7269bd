// Spline values (`attr.spline = { ... }`, OpenUSD 25.05), after the grammar of
// sdf/textFileFormatParser.h (SplineValue) and what Sdf_FileIOUtility::WriteSpline writes:
//   bezier,                          curve type (or hermite)
//   pre: held,                       extrapolation: none, held, linear, sloped(s), loop repeat|reset|oscillate
//   post: sloped(0.5),
//   loop: (15, 25, 0, 2, 11.7),      inner loop: protoStart, protoEnd, numPreLoops, numPostLoops, valueOffset
//   7: 5.5 & 7.21; post held,        knot: time: [preValue &] value; parameters after ';'
//   15: 8; post curve ws(2.5, 1.2); { string comment = "x" },
//   20: 14; pre ws(3.8, -1.4); post curve ws(1.1, -1.4),
// Tangents: ws(width, slope) and s(slope) in Ts's standard form, wh(width, height) and h(height)
// in Maya's (width three times Ts's, height = slope * width, a pre-tangent's height negated:
// ts/tangentConversions.cpp, eval.cpp's _GetCurveKnotSlope); a Hermite's Maya width is its segment.
#include "harness/usda/usda_parser.h"

#include <cmath>
#include <limits>
#include <map>

namespace obscura::usda {

namespace {

// A Hermite knot's Maya-form heights wait for its neighbours, whose distance is their width.
struct ParsedKnot {
    SplineKnot knot;
    std::optional<double> preHeight, postHeight;
};

}  // namespace

void Parser::skipBraceBlock(const std::string& what) {
    const Token open = expect('{', "to open the " + what);
    std::string closers = "}";
    while (!closers.empty()) {
        const Token token = take();
        if (token.kind == TokenKind::EndOfFile) fail(open, "the " + what + " opened here is not closed");
        if (token.isPunct('{')) closers.push_back('}');
        else if (token.isPunct('[')) closers.push_back(']');
        else if (token.isPunct('(')) closers.push_back(')');
        else if (token.kind == TokenKind::Punct && (token.isPunct('}') || token.isPunct(']') || token.isPunct(')'))) {
            if (!token.isPunct(closers.back())) fail(token, "unbalanced '" + std::string(token.text) + "' in the " + what);
            closers.pop_back();
        }
    }
}

double Parser::parseSplineNumber(const std::string& what) {
    const Token token = take();
    if (token.kind != TokenKind::Number && !token.isWord("inf") && !token.isWord("nan"))
        fail(token, "expected a number for " + what + " in the spline, found " + describe(token));
    return toNumber(token);
}

int Parser::parseSplineLoopCount(const std::string& what) {
    const Token token = take();
    const double count = token.kind == TokenKind::Number ? toNumber(token) : 0.5;
    if (!(count >= std::numeric_limits<int>::min() && count <= std::numeric_limits<int>::max()) ||
        count != std::floor(count))
        fail(token, "expected a whole number for " + what + " in the spline, found " + describe(token));
    return static_cast<int>(count);
}

SplineExtrapolation Parser::parseSplineExtrapolation(const Token& mode) {
    using Mode = SplineExtrapolationMode;
    if (mode.isWord("none")) return {Mode::None};
    if (mode.isWord("held")) return {Mode::Held};
    if (mode.isWord("linear")) return {Mode::Linear};
    if (mode.isWord("sloped")) {
        expect('(', "after 'sloped'");
        const double slope = parseSplineNumber("the extrapolation slope");
        expect(')', "after the extrapolation slope");
        return {Mode::Sloped, slope};
    }
    if (mode.isWord("loop")) {
        const Token kind = take();
        if (kind.isWord("repeat")) return {Mode::LoopRepeat};
        if (kind.isWord("reset")) return {Mode::LoopReset};
        if (kind.isWord("oscillate")) return {Mode::LoopOscillate};
        fail(kind, "expected 'repeat', 'reset' or 'oscillate' after 'loop', found " + describe(kind));
    }
    fail(mode, "expected an extrapolation (none, held, linear, sloped(slope) or loop repeat|reset|oscillate), found " +
                   describe(mode));
}

SplineLoop Parser::parseSplineLoop() {
    expect('(', "after 'loop:'");
    SplineLoop loop;
    loop.protoStart = parseSplineNumber("the loop's prototype start");
    expect(',', "after the loop's prototype start");
    loop.protoEnd = parseSplineNumber("the loop's prototype end");
    expect(',', "after the loop's prototype end");
    loop.numPreLoops = parseSplineLoopCount("the loop's count before");
    expect(',', "after the loop's count before");
    loop.numPostLoops = parseSplineLoopCount("the loop's count after");
    expect(',', "after the loop's count after");
    loop.valueOffset = parseSplineNumber("the loop's value offset");
    expect(')', "after the loop's value offset");
    return loop;
}

std::shared_ptr<const Spline> Parser::parseSpline(const ValueType& type) {
    const Token open = expect('{', "to open the spline");
    NestingGuard guard(*this, open);
    auto spline = std::make_shared<Spline>();
    spline->valueType = type.name;
    std::map<double, ParsedKnot> knots;
    skipNewlines();
    while (!peek().isPunct('}')) {
        const Token item = take();
        std::string_view label = item.text;
        // "pre:held" without a space reads as one namespaced name.
        std::optional<Token> fusedMode;
        if (item.kind == TokenKind::Identifier && (label.starts_with("pre:") || label.starts_with("post:"))) {
            fusedMode = item;
            fusedMode->text = label.substr(label.find(':') + 1);
            label = label.substr(0, label.find(':'));
        }
        if (item.isWord("bezier") || item.isWord("hermite")) {
            spline->hermite = item.isWord("hermite");
        } else if (label == "pre" || label == "post") {
            if (!fusedMode) expect(':', "after '" + std::string(label) + "'");
            (label == "pre" ? spline->pre : spline->post) = parseSplineExtrapolation(fusedMode ? *fusedMode : take());
        } else if (item.isWord("loop")) {
            expect(':', "after 'loop'");
            spline->loop = parseSplineLoop();
        } else if (item.kind == TokenKind::Number) {
            ParsedKnot parsed;
            SplineKnot& knot = parsed.knot;
            knot.time = toNumber(item);
            expect(':', "after the knot time");
            knot.value = parseSplineNumber("the knot value");
            if (accept('&')) {
                knot.preValue = knot.value;
                knot.value = parseSplineNumber("the knot value after '&'");
            }
            while (accept(';')) {
                if (peek().isPunct('{')) {
                    // Custom data, kept by Ts for tools; it does not shape the curve.
                    std::map<std::string, Value> ignored;
                    parseDictionary("", ignored);
                    continue;
                }
                const Token param = take();
                if (param.isWord("pre")) {
                    parseSplineKnotTangent(true, spline->hermite, knot, parsed.preHeight);
                } else if (param.isWord("post")) {
                    const Token mode = take();
                    if (mode.isWord("none")) knot.next = SplineInterpolation::None;
                    else if (mode.isWord("held")) knot.next = SplineInterpolation::Held;
                    else if (mode.isWord("linear")) knot.next = SplineInterpolation::Linear;
                    else if (mode.isWord("curve")) knot.next = SplineInterpolation::Curve;
                    else fail(mode, "expected none, held, linear or curve after 'post', found " + describe(mode));
                    if (peek().kind == TokenKind::Identifier) parseSplineKnotTangent(false, spline->hermite, knot, parsed.postHeight);
                } else {
                    fail(param, "expected 'pre', 'post' or a dictionary after ';' in a spline knot, found " + describe(param));
                }
            }
            if (!knots.emplace(knot.time, parsed).second)
                fail(item, "the spline has two knots at time " + std::string(item.text));
        } else {
            fail(item, "expected 'bezier', 'hermite', 'pre:', 'post:', 'loop:' or a knot 'time: value' in the spline, found " +
                           describe(item));
        }
        skipNewlines();
        if (accept(',')) {
            skipNewlines();
        } else if (!peek().isPunct('}')) {
            fail(peek(), "expected ',' or '}' after a spline item, found " + describe(peek()));
        }
    }
    take();
    for (auto it = knots.begin(); it != knots.end(); ++it) {
        SplineKnot& knot = it->second.knot;
        if (it->second.preHeight && it != knots.begin())
            knot.preSlope = slopeOfMayaTangent(true, *it->second.preHeight, knot.time - std::prev(it)->first);
        if (it->second.postHeight && std::next(it) != knots.end())
            knot.postSlope = slopeOfMayaTangent(false, *it->second.postHeight, std::next(it)->first - knot.time);
        spline->knots.push_back(knot);
    }
    return spline;
}

void Parser::parseSplineKnotTangent(bool isPre, bool hermite, SplineKnot& knot, std::optional<double>& hermiteHeight) {
    const Token form = take();
    if (form.kind != TokenKind::Identifier)
        fail(form, "expected a tangent (ws, wh, s or h) in a spline knot, found " + describe(form));
    expect('(', "after the tangent form '" + std::string(form.text) + "'");
    const double first = parseSplineNumber("the tangent");
    std::optional<double> second;
    if (accept(',')) second = parseSplineNumber("the tangent");
    expect(')', "after the tangent");
    const bool withWidth = form.isWord("ws") || form.isWord("wh");
    if (!withWidth && !form.isWord("s") && !form.isWord("h"))
        fail(form, "unknown spline tangent form '" + std::string(form.text) + "' (ws, wh, s or h)");
    if (withWidth != second.has_value())
        fail(form, "the tangent form '" + std::string(form.text) + "' takes " + (withWidth ? "two numbers" : "one number"));
    double& width = isPre ? knot.preWidth : knot.postWidth;
    double& slope = isPre ? knot.preSlope : knot.postSlope;
    if (form.isWord("ws")) {
        width = hermite ? width : first;
        slope = *second;
    } else if (form.isWord("s")) {
        slope = first;
    } else if (form.isWord("wh")) {
        width = hermite ? width : first / 3.0;
        slope = slopeOfMayaTangent(isPre, *second, first);
    } else if (hermite) {
        hermiteHeight = first;
    } else {
        // A Bezier's Maya height without a width: over its (standard) width, as Ts divides.
        slope = slopeOfMayaTangent(isPre, first, 3.0 * width);
    }
}

}  // namespace obscura::usda
