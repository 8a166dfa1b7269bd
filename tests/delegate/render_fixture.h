// Shared scene pieces for delegate tests: a camera looking down -Z at a plane, lights and
// materials, and the helpers that turn pixels into the analytic expectations.
#pragma once

#include "harness/image/compare.h"
#include "tests/support/test_host.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace obscura::test {

constexpr int kWidth = 64;
constexpr int kHeight = 64;
constexpr double kPi = std::numbers::pi;

// Rotation taking the light's local -Z axis (its emission direction) onto `direction`.
Matrix lightPointingAlong(std::array<double, 3> direction);

// The delegate's counters after the last render.
ObscuraRenderStats renderStats(TestHost& host);

// Sets a numeric (or boolean: 0/1) render setting; a refusal fails the test.
void setNumber(TestHost& host, const char* name, double value);
void setToken(TestHost& host, const char* name, const std::string& value);
// Sets a boolean render setting as a host passing OBSCURA_VALUE_BOOL does.
void setBool(TestHost& host, const char* name, bool on);

// A unit-normal quad of half-size `half` at z = 0 facing +Z, with a material bound.
void addPlane(TestHost& host, const std::string& path, const std::string& material, double half = 10.0,
              Matrix transform = identity());
void addMaterial(TestHost& host, const std::string& path, std::array<float, 3> diffuse, float roughness = 1.0f,
                 float metallic = 0.0f, std::array<float, 3> emissive = {0, 0, 0});

// One step of a B10G11R11_UFLOAT channel at `v` (mantissa bits: 6 for R and G, 5 for B). The
// accumulation buffer holds radiance to this step; conversion may round or truncate (both are
// allowed by Vulkan), so analytic expectations get this much slack on top of their tolerance.
float smallFloatStep(float v, int mantissaBits);

// The IEC 61966-2-1 decode of an sRGB-encoded value in [0, 1], and its inverse.
float srgbDecode(double encoded);
float srgbEncode(double linear);
// A linear value that 8-bit sRGB storage (the albedo G-buffer target) holds exactly.
float srgb8Exact(int code);

// Karis 2014's analytic fit of the split-sum DFG term: the response to a constant environment is
// L (F0 A + B), the fit the lighting pass uses for domes (brdf.glsl). Returns {A, B}.
std::array<double, 2> environmentBrdf(double roughness, double NdotV);

// World-space point on the z = 0 plane seen through the centre of pixel (x, y) of a square image
// `size` pixels wide by a camera at (0, 0, distance) looking down -Z with the given tan of the
// half field of view.
std::array<double, 3> planePointAtPixel(int x, int y, double distance, double tanHalfFov, int size = kWidth);

// A grey Lambert plane (albedo 0.5029, a value 8-bit sRGB holds exactly, so the G-buffer adds no
// error of its own) at z = 0 facing +Z, seen by a camera at (0, 0, 5) looking down -Z; tests add
// lights and read the linear colour AOV.
constexpr double kLitPlaneCameraDistance = 5.0;
constexpr float kLitPlaneFocalLength = 50.0f, kLitPlaneAperture = 20.955f;
constexpr double kLitPlaneTanHalfFov = (kLitPlaneAperture / 2.0) / kLitPlaneFocalLength;
extern const float kLitPlaneAlbedo;

// Irradiance from a uniform disk of radiance L and radius r parallel to the receiver, its plane h
// above it and its axis rho to the side (the configuration factor of a differential area to a
// parallel disk, Howell's catalogue B-4).
double diskIrradiance(double radiance, double r, double h, double rho);

struct LitPlaneScene {
    TestHost host;
    LitPlaneScene();
    std::vector<float> renderColor();
};

// The lit plane's camera and colour buffer, and a sun of `irradiance` shining straight down -Z
// without a specular response: for tests that bring their own surfaces at z = 0.
void addLitPlaneViewAndSun(TestHost& host, double irradiance);

// The pixel's radiance equals `expected` within 1% plus one step of the B10G11R11 accumulation
// format (mantissa 6, 6, 5 bits: 1.6% for R and G, 3.1% for B).
void expectRadiance(const std::vector<float>& color, int x, int y, std::array<double, 3> expected);

// A closed box mesh between corners `lo` and `hi` (six quads, outward normals) with a material.
void addBox(TestHost& host, const std::string& path, std::array<double, 3> lo, std::array<double, 3> hi,
            const std::string& material);

// A camera at `eye` looking along +Y, pitched down by `pitchDegrees` (Z is up).
Matrix lookingAlongY(std::array<double, 3> eye, double pitchDegrees);

// Rotation by `degrees` about Z (counter-clockwise seen from +Z), then a translation.
Matrix turnedAndMoved(double degrees, double x, double y, double z);

// The RGB channels of a colour AOV (RGBA floats, rows from the top) as an image.
image::Image rgbImage(const std::vector<float>& rgba, int width, int height);

// The box filter over each pixel: the mean of its factor x factor supersamples, each passed
// through `transfer` first (identity: the plain supersampled image).
image::Image boxDownsample(const std::vector<float>& rgba, int width, int height, int factor,
                           float (*transfer)(float) = nullptr);

// PSNR, SSIM and errors of `a` against `b` (a failed comparison fails the test).
image::CompareMetrics compareImages(const image::Image& a, const image::Image& b);

}  // namespace obscura::test
