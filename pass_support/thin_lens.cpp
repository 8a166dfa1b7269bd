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

// The diaphragm's polygon over a disc point (radius, angle) of the concentric mapping: within the
// sector of the blade whose edge's middle lies nearest, the angle from that middle, phi0 in
// [-pi/n, pi/n), uniform in area over the disc, becomes phi = atan(tan(pi/n) phi0 / (pi/n)), whose
// density 1 / cos^2 phi is the polygon's, and the radius reaches the edge at cos(pi/n) / cos(phi).
Polar polygonFromDisc(Polar disc, const ApertureShape& shape) {
    double n = shape.blades, half = kPi / n;
    double local = disc.angle - shape.rotation;
    double middle = 2.0 * half * std::floor((local + half) / (2.0 * half));
    double phi = std::atan(std::tan(half) * (local - middle) / half);
    return {disc.radius * std::cos(half) / std::cos(phi), shape.rotation + middle + phi};
}

}  // namespace

bool hasDepthOfField(const ThinLens& lens) {
    return lens.fStop > 0.0 && lens.focalLength > 0.0 && lens.focusDistance > lens.focalLength && lens.filmWidth > 0.0;
}

double apertureDiameter(const ThinLens& lens) { return lens.fStop > 0.0 ? lens.focalLength / lens.fStop : 0.0; }

double circleOfConfusionDiameter(const ThinLens& lens, double distance) {
    return apertureDiameter(lens) * lens.focalLength * std::fabs(1.0 / distance - 1.0 / lens.focusDistance);
}

double accumulationApertureDiameter(const ThinLens& lens) { return hasDepthOfField(lens) ? apertureDiameter(lens) : 0.0; }

CocFromDepth cocFromDepth(const ThinLens& lens, double nearClip, double farClip, double imageWidthPixels) {
    if (!hasDepthOfField(lens)) return {};
    double F = lens.focalLength, P = lens.focusDistance, A = apertureDiameter(lens);
    // Signed radius on the film A F (1 / D - 1 / P) / 2 = k (P / D - 1), in pixels.
    double k = 0.5 * A * F / P * (imageWidthPixels / lens.filmWidth);
    double inverseNear = 1.0 / nearClip, inverseFar = 1.0 / farClip;
    return {k * P * (inverseFar - inverseNear), k * (P * inverseNear - 1.0)};
}

ApertureShape apertureShape(int blades, double rotationDegrees) {
    ApertureShape shape;
    shape.blades = blades >= 3 ? blades : 0;
    shape.rotation = rotationDegrees * kPi / 180.0;
    return shape;
}

std::array<double, 2> sampleAperture(std::array<double, 2> square, const ApertureShape& shape) {
    Polar p = concentricDisc(square[0], square[1]);
    if (shape.blades >= 3) p = polygonFromDisc(p, shape);
    return {p.radius * std::cos(p.angle), p.radius * std::sin(p.angle)};
}

double ApertureCell::share() const { return std::sqrt(halfSize[0] * halfSize[1]); }

double apertureCellReach(const ApertureCell& cell, const ApertureShape& shape) {
    // The farthest point lies on the cell's boundary: walk it finely.
    constexpr int kStepsPerSide = 64;
    std::array<double, 2> centre = sampleAperture(cell.centre, shape);
    double reach = 0.0;
    for (int side = 0; side < 4; ++side)
        for (int i = 0; i <= kStepsPerSide; ++i) {
            double t = 2.0 * i / kStepsPerSide - 1.0, u = side < 2 ? t : (side == 2 ? -1.0 : 1.0),
                   v = side < 2 ? (side == 0 ? -1.0 : 1.0) : t;
            std::array<double, 2> p = sampleAperture(
                {cell.centre[0] + cell.halfSize[0] * u, cell.centre[1] + cell.halfSize[1] * v}, shape);
            reach = std::max(reach, std::hypot(p[0] - centre[0], p[1] - centre[1]));
        }
    return reach;
}

std::array<double, 2> squareGridCell(int index, int side) {
    int column = index % side, row = index / side;
    return {(2.0 * column + 1.0) / side - 1.0, (2.0 * row + 1.0) / side - 1.0};
}

}  // namespace obscura::passes
