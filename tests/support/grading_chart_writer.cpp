#include "tests/support/grading_chart_writer.h"

#include "harness/image/png_io.h"

#include <obscura/grading_chart.h>

#include <unistd.h>

#include <filesystem>
#include <stdexcept>

namespace obscura::test {

std::string writeGradedChart(const std::string& name, const std::function<float(float)>& grade, int extra) {
    auto path = std::filesystem::temp_directory_path() / ("obscura_" + name + "_" + std::to_string(getpid()) + ".png");
    auto chart = image::Image::make(int(OBSCURA_GRADING_CHART_WIDTH) + extra, int(OBSCURA_GRADING_CHART_HEIGHT) + extra,
                                    {"R", "G", "B"});
    for (float& v : chart.pixels) v = 0.5f;
    for (uint32_t y = 0; y < OBSCURA_GRADING_CHART_HEIGHT; ++y)
        for (uint32_t x = 0; x < OBSCURA_GRADING_CHART_WIDTH; ++x) {
            uint8_t rgb[3];
            obscuraGradingChartNeutral(x, y, rgb);
            for (int c = 0; c < 3; ++c) chart.pixels[chart.index(int(x), int(y), c)] = grade(rgb[c] / 255.0f);
        }
    if (auto written = image::writePng(path.string(), chart); image::isError(written))
        throw std::runtime_error(image::errorOf(written));
    return path.string();
}

}  // namespace obscura::test
