// The graded chart that the render setting `grading:chart` names (seed 004 "Color grading": the
// LUT read back from an image an artist graded; layout in <obscura/grading_chart.h>).
#pragma once

#include "pass_support/grading_lattice.h"

#include <optional>
#include <string>
#include <variant>

namespace obscura::renderer {

// Reads the chart in the top-left corner of an image (8 or 16 bits a channel, any format
// stb_image reads) into a lattice of display values. Returns the reason when it cannot.
std::variant<passes::GradingLattice, std::string> readGradingChart(const std::string& path);

// The chart file of the current setting, read again only when the path or the file changes.
class GradingChartFile {
public:
    // "" turns the grade off. Returns the reason on failure (the grade is then off).
    std::string load(const std::string& path);
    const passes::GradingLattice* lattice() const { return lattice_ ? &*lattice_ : nullptr; }
    // Names what is loaded: the path and the file's modification time.
    const std::string& key() const { return key_; }

private:
    std::string reload(const std::string& path);
    std::string key_;
    std::optional<passes::GradingLattice> lattice_;
};

}  // namespace obscura::renderer
