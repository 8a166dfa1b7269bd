// A scene for the camera effects' tests (depth of field, motion blur): a USD camera at the origin
// looking down -Z with a given lens, a float colour buffer, SSAO off, and the helpers that read
// the colour AOV as an image and compare it with the reference mode's.
#pragma once

#include "tests/delegate/render_fixture.h"

#include "harness/image/compare.h"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace obscura::test {

// A USD camera's lens, in USD units: focal length and film in tenths of a scene unit.
struct Lens {
    float focalLength = 50.0f;
    float filmWidth = 20.955f;
    float fStop = 0.0f;
    float focusDistance = 0.0f;
    int blades = 0;
    float rotationDegrees = 0.0f;
};

// How a chequered card's cells are told apart: faces of their own colour (edges the raster
// anti-aliases) or texels of an 8-bit sRGB texture (edges the texture filter anti-aliases).
enum class Chequer { Geometry, Texture };

struct CameraScene {
    TestHost host;
    int width, height;
    CameraScene(const Lens& lens, int w, int h);
    void setNumber(const char* name, double value);
    // UsdGeomCamera shutter:open / shutter:close, in time codes relative to the frame.
    void setShutter(double open, double close);
    image::Image render(double time = 0.0);
    image::Image renderReference(int subFrames, double time = 0.0);
    // A card of cells_x x cells_y chequered cells centred at `centre`, facing +Z (the camera). As
    // a texture, 16 texels a cell, clamped at its border.
    void addChequerCard(Chequer kind, const std::string& path, std::array<double, 3> centre, double cellSize,
                        int cellsX, int cellsY, std::array<float, 3> light, std::array<float, 3> dark);
    ~CameraScene();

private:
    std::filesystem::path files_;  // the scene's textures, made on first use
};

// CameraScene::addChequerCard's card of faces, in any host.
void addChequerCard(TestHost& host, const std::string& path, std::array<double, 3> centre, double cellSize,
                    int cellsX, int cellsY, std::array<float, 3> light, std::array<float, 3> dark);

image::CompareMetrics metrics(const image::Image& a, const image::Image& b);
// PSNR (peak 1) of linear RGB mapped by x / (1 + x) first, the fidelity metric of comparisons
// with path-traced ground truth: errors weigh as a display shows them, not by their linear size.
double mappedPsnr(const image::Image& a, const image::Image& b);
image::Image crop(const image::Image& img, int x0, int y0, int x1, int y1);

// The frame-graph passes of the last render, by name.
std::vector<std::string> passNames(TestHost& host);
bool ranPass(TestHost& host, const std::string& name);

}  // namespace obscura::test
