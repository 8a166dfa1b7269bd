// obscura grade-chart: the neutral colour-grading chart (seed 004 "Color grading": graded in an
// image editor, then read back as the LUT by the render setting grading:chart).
#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/image/png_io.h"

#include <obscura/grading_chart.h>

#include <algorithm>
#include <cstdio>

namespace obscura::harness {

int runGradeChart(const GradeChartOptions& options) {
    image::Image out = image::Image::make(OBSCURA_GRADING_CHART_WIDTH, OBSCURA_GRADING_CHART_HEIGHT, {"R", "G", "B"});
    if (!options.into.empty()) {
        // Over a screenshot: the artist grades the frame and the chart together.
        auto shot = image::readStbImage(options.into);
        if (image::isError(shot)) {
            std::fprintf(stderr, "obscura: %s\n", image::errorOf(shot).c_str());
            return kExitBadInput;
        }
        const image::Image& frame = std::get<image::Image>(shot);
        out = image::Image::make(std::max<int>(frame.width, OBSCURA_GRADING_CHART_WIDTH),
                                 std::max<int>(frame.height, OBSCURA_GRADING_CHART_HEIGHT), {"R", "G", "B"});
        for (int y = 0; y < frame.height; ++y)
            for (int x = 0; x < frame.width; ++x)
                for (int c = 0; c < 3; ++c) out.pixels[out.index(x, y, c)] = frame.pixels[frame.index(x, y, c)];
    }
    for (uint32_t y = 0; y < OBSCURA_GRADING_CHART_HEIGHT; ++y)
        for (uint32_t x = 0; x < OBSCURA_GRADING_CHART_WIDTH; ++x) {
            uint8_t rgb[3];
            obscuraGradingChartNeutral(x, y, rgb);
            for (int c = 0; c < 3; ++c) out.pixels[out.index(int(x), int(y), c)] = rgb[c] / 255.0f;
        }
    if (auto written = image::writePng(options.output, out); image::isError(written)) {
        std::fprintf(stderr, "obscura: %s\n", image::errorOf(written).c_str());
        return kExitBadInput;
    }
    std::printf("grading chart (%ux%u, a %u^3 lattice) written to %s: grade it, then render with "
                "--set grading:chart=GRADED.png\n",
                OBSCURA_GRADING_CHART_WIDTH, OBSCURA_GRADING_CHART_HEIGHT, OBSCURA_GRADING_CHART_LATTICE,
                options.output.c_str());
    return kExitOk;
}

}  // namespace obscura::harness
