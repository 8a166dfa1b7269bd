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
    for (uint32_t b = 0; b < OBSCURA_GRADING_CHART_LATTICE; ++b)
        for (uint32_t g = 0; g < OBSCURA_GRADING_CHART_LATTICE; ++g)
            for (uint32_t r = 0; r < OBSCURA_GRADING_CHART_LATTICE; ++r) {
                uint32_t x = 0, y = 0;
                obscuraGradingChartPixel(r, g, b, &x, &y);
                const uint32_t index[3] = {r, g, b};
                for (int c = 0; c < 3; ++c)
                    chart.pixels[chart.index(int(x), int(y), c)] = grade(obscuraGradingChartValue(index[c]) / 255.0f);
            }
    if (auto written = image::writePng(path.string(), chart); image::isError(written))
        throw std::runtime_error(image::errorOf(written));
    return path.string();
}

}  // namespace obscura::test
