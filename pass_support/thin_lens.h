// The physical camera of depth of field (seed 000, "Depth of field"): the circle of confusion of a
// thin lens and the shape of its aperture. The post-process filter (depth_of_field.h) and the
// reference mode's lens sampling (the delegate's accumulation of sub-frames) share these, and
// shaders/common/dof_common.glsl mirrors the aperture mapping for the GPU: change them together.
#pragma once

#include <array>

namespace obscura::passes {

// A lens as USD's camera describes it, in scene units (USD's tenths of a scene unit converted).
struct ThinLens {
    double focalLength = 0.0;    // F
    double fStop = 0.0;          // f = F / A; 0: a pinhole, no depth of field (as in USD)
    double focusDistance = 0.0;  // P, from the lens to the plane in focus
    double filmWidth = 0.0;      // the film gate the image spans horizontally (after conforming)
};

// True when the lens blurs anything: fStop > 0 and a focus plane beyond the focal length (a plane
// at or inside F has no real image, so the thin-lens equation has no answer there).
bool hasDepthOfField(const ThinLens& lens);

// Aperture diameter A = F / f.
double apertureDiameter(const ThinLens& lens);

// Diameter of the circle of confusion on the film, in scene units, of a point at distance D along
// the view axis (Potmesil & Chakravarty 1981; seed 000 "Lens review (2)"):
//   CoC = |F D / (D - F) - F P / (P - F)| * (D - F) / (f D).
double circleOfConfusionDiameter(const ThinLens& lens, double distance);

// The lens diameter of an accumulation-buffer camera (pinholes spread over the lens, projecting
// onto a film at the focal length, the focus plane held fixed: the reference mode) whose blur is
// the CoC above. Potmesil's CoC lies on a film at the image distance I = F P / (P - F), while USD
// fixes the field of view by F alone (no focus breathing), so the pinholes spread over A I / F.
double accumulationApertureDiameter(const ThinLens& lens);

// The slide's simplification CoC = |A F (P - D) / (D (P - F))| is affine in 1/D, and a perspective
// depth buffer is affine in 1/D too (1/D = 1/near + depth * (1/far - 1/near)), so the signed CoC
// radius in pixels is one multiply-add per pixel: radius = depth * scale + bias ("folds down into
// a single mad in shader"). Positive in front of the focus plane (near field), negative behind it.
struct CocFromDepth {
    double scale = 0.0;
    double bias = 0.0;
    double radiusPixels(double depth) const { return depth * scale + bias; }
};
CocFromDepth cocFromDepth(const ThinLens& lens, double nearClip, double farClip, double imageWidthPixels);

// The diaphragm (seed 000 "Plausible DOF: Bokeh", "Sampling"): `blades` straight blades (0: a
// circle) rotated by `rotation`, polygonal when stopped down and rounder wide open.
struct ApertureShape {
    int blades = 0;
    double rotation = 0.0;       // radians, counter-clockwise; the slide's theta_shutter_max
    double polygonBlend = 0.0;   // the slide's f: 0 a circle, 1 the full polygon
};

// The slide's f-stop interpolation f = (fstops - fstops_min) / (fstops_max - fstops_min), clamped
// to [0, 1]: a circle at f/1 and wider, the full polygon from f/8 on.
constexpr double kRoundApertureFStop = 1.0;
constexpr double kPolygonalApertureFStop = 8.0;
ApertureShape apertureShape(int blades, double rotationDegrees, double fStop);

// A point of the unit square [-1, 1]^2 on the aperture, whose circumscribed circle is the unit
// disc (x right, y up as seen from behind the camera), and the area the mapping gives a unit of
// the square there, relative to a circular aperture:
// 1. concentric mapping (Shirley & Chiu 1997), area-preserving square -> disc: in the first
//    region r = a, theta = pi b / (4 a);
// 2. diaphragm: r_ngon = r (cos(pi / n) / cos(theta - (2 pi / n) floor((n theta + pi) / (2 pi))))^f,
//    theta += f theta_shutter_max. The polygon is inscribed in the unit circle; at rotation 0 the
//    middle of an edge faces +x. The radial scale g^f stretches area by g^(2f): the returned
//    `area` lets a sum over evenly spread square points weight the aperture evenly (a flat
//    bokeh kernel, "Plausible DOF: Bokeh").
struct ApertureSample {
    std::array<double, 2> position;
    double area;
};
ApertureSample sampleAperture(std::array<double, 2> square, const ApertureShape& shape);

// The centre of cell `index` (row-major) of a side x side grid over [-1, 1]^2: the gather passes'
// taps (a square kernel, seed 000 "Sampling") before the mapping above.
std::array<double, 2> squareGridCell(int index, int side);

}  // namespace obscura::passes
