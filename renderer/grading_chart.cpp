#include "renderer/grading_chart.h"

#include <obscura/grading_chart.h>

#include <stb_image.h>

#include <filesystem>
#include <memory>
#include <system_error>

namespace obscura::renderer {

std::variant<passes::GradingLattice, std::string> readGradingChart(const std::string& path) {
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<stbi_us, void (*)(void*)> data(stbi_load_16(path.c_str(), &width, &height, &channels, 3),
                                                   stbi_image_free);
    if (!data) {
        const char* reason = stbi_failure_reason();
        return std::string("cannot read image: ") + (reason ? reason : "unknown error");
    }
    if (uint32_t(width) < OBSCURA_GRADING_CHART_WIDTH || uint32_t(height) < OBSCURA_GRADING_CHART_HEIGHT)
        return "the image is " + std::to_string(width) + "x" + std::to_string(height) + ", smaller than the " +
               std::to_string(OBSCURA_GRADING_CHART_WIDTH) + "x" + std::to_string(OBSCURA_GRADING_CHART_HEIGHT) +
               " chart its top-left corner must hold (obscura grade-chart --write makes one)";
    passes::GradingLattice lattice;
    lattice.size = OBSCURA_GRADING_CHART_LATTICE;
    lattice.values.resize(size_t(lattice.size) * lattice.size * lattice.size);
    for (uint32_t b = 0; b < lattice.size; ++b)
        for (uint32_t g = 0; g < lattice.size; ++g)
            for (uint32_t r = 0; r < lattice.size; ++r) {
                uint32_t x = 0, y = 0;
                obscuraGradingChartPixel(r, g, b, &x, &y);
                const stbi_us* texel = data.get() + (size_t(y) * uint32_t(width) + x) * 3;
                lattice.values[(size_t(b) * lattice.size + g) * lattice.size + r] = {
                    texel[0] / 65535.0f, texel[1] / 65535.0f, texel[2] / 65535.0f};
            }
    return lattice;
}

std::string GradingChartFile::load(const std::string& path) {
    std::string problem = path.empty() ? std::string() : reload(path);
    if (path.empty() || !problem.empty()) {
        key_.clear();
        lattice_.reset();
    }
    return problem.empty() ? problem : "grading:chart '" + path + "': " + problem;
}

std::string GradingChartFile::reload(const std::string& path) {
    std::error_code error;
    const auto modified = std::filesystem::last_write_time(path, error);
    if (error) return error.message();
    std::string key = path + '\n' + std::to_string(modified.time_since_epoch().count());
    if (key == key_ && lattice_) return {};
    auto read = readGradingChart(path);
    if (auto* reason = std::get_if<std::string>(&read)) return *reason;
    lattice_ = std::move(std::get<passes::GradingLattice>(read));
    key_ = std::move(key);
    return {};
}

}  // namespace obscura::renderer
