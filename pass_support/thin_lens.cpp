#include "pass_support/thin_lens.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::passes {
namespace {

constexpr double kPi = std::numbers::pi;

struct Polar {
    double radius;
    double angle;
};

// Shirley & Chiu 1997: the square's concentric squares become concentric circles; each of the four
// regions between the diagonals a = b and a = -b maps to a quarter of the disc.
Polar concentricDisc(double a, double b) {
    if (a == 0.0 && b == 0.0) return {0.0, 0.0};
    if (std::fabs(a) > std::fabs(b)) {
        double angle = kPi / 4.0 * (b / a);
        return a > 0.0 ? Polar{a, angle} : Polar{-a, angle + kPi};
    }
    double angle = kPi / 2.0 - kPi / 4.0 * (a / b);
    return b > 0.0 ? Polar{b, angle} : Polar{-b, angle + kPi};
}

// Radius of the regular polygon inscribed in the unit circle along `angle` (seed 000 "Sampling").
double polygonRadius(double angle, int blades) {
    double n = blades;
    double sector = angle - (2.0 * kPi / n) * std::floor((n * angle + kPi) / (2.0 * kPi));
    return std::cos(kPi / n) / std::cos(sector);
}

}  // namespace

bool hasDepthOfField(const ThinLens& lens) {
    return lens.fStop > 0.0 && lens.focalLength > 0.0 && lens.focusDistance > lens.focalLength && lens.filmWidth > 0.0;
}

double apertureDiameter(const ThinLens& lens) { return lens.fStop > 0.0 ? lens.focalLength / lens.fStop : 0.0; }

double circleOfConfusionDiameter(const ThinLens& lens, double distance) {
    double F = lens.focalLength, P = lens.focusDistance, D = distance;
    return std::fabs(F * D / (D - F) - F * P / (P - F)) * (D - F) / (lens.fStop * D);
}

double accumulationApertureDiameter(const ThinLens& lens) {
    if (!hasDepthOfField(lens)) return 0.0;
    return apertureDiameter(lens) * lens.focusDistance / (lens.focusDistance - lens.focalLength);
}

CocFromDepth cocFromDepth(const ThinLens& lens, double nearClip, double farClip, double imageWidthPixels) {
    if (!hasDepthOfField(lens)) return {};
    double F = lens.focalLength, P = lens.focusDistance, A = apertureDiameter(lens);
    // Signed radius on the film A F (P - D) / (2 D (P - F)) = k (P / D - 1), in pixels.
    double k = 0.5 * A * F / (P - F) * (imageWidthPixels / lens.filmWidth);
    double inverseNear = 1.0 / nearClip, inverseFar = 1.0 / farClip;
    return {k * P * (inverseFar - inverseNear), k * (P * inverseNear - 1.0)};
}

ApertureShape apertureShape(int blades, double rotationDegrees, double fStop) {
    ApertureShape shape;
    shape.blades = blades >= 3 ? blades : 0;
    shape.rotation = rotationDegrees * kPi / 180.0;
    double f = (fStop - kRoundApertureFStop) / (kPolygonalApertureFStop - kRoundApertureFStop);
    shape.polygonBlend = shape.blades ? std::clamp(f, 0.0, 1.0) : 0.0;
    return shape;
}

ApertureSample sampleAperture(std::array<double, 2> square, const ApertureShape& shape) {
    Polar p = concentricDisc(square[0], square[1]);
    double scale = 1.0;
    if (shape.blades >= 3 && shape.polygonBlend > 0.0)
        scale = std::pow(polygonRadius(p.angle, shape.blades), shape.polygonBlend);
    double radius = p.radius * scale, angle = p.angle + shape.polygonBlend * shape.rotation;
    return {{radius * std::cos(angle), radius * std::sin(angle)}, scale * scale};
}

std::array<double, 2> squareGridCell(int index, int side) {
    int column = index % side, row = index / side;
    return {(2.0 * column + 1.0) / side - 1.0, (2.0 * row + 1.0) / side - 1.0};
}

}  // namespace obscura::passes
