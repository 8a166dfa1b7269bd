#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/image/compare.h"
#include "harness/image/image_file.h"
#include "harness/image/png_io.h"

#include <cmath>
#include <cstdio>

namespace obscura::harness {

int runCompare(const CompareOptions& o) {
    auto a = image::readImage(o.a);
    if (image::isError(a)) {
        std::fprintf(stderr, "obscura: %s\n", image::errorOf(a).c_str());
        return kExitBadInput;
    }
    auto b = image::readImage(o.b);
    if (image::isError(b)) {
        std::fprintf(stderr, "obscura: %s\n", image::errorOf(b).c_str());
        return kExitBadInput;
    }
    const auto& ia = std::get<image::Image>(a);
    const auto& ib = std::get<image::Image>(b);
    auto metrics = image::compare(ia, ib);
    if (image::isError(metrics)) {
        std::fprintf(stderr, "obscura: %s\n", image::errorOf(metrics).c_str());
        return kExitBadInput;
    }
    const auto& m = std::get<image::CompareMetrics>(metrics);
    std::printf("psnr %.4f dB\nssim %.6f\nmax_abs_error %.6g\nmean_abs_error %.6g\nrmse %.6g\n", m.psnr, m.ssim,
                m.maxAbsError, m.meanAbsError, m.rmse);
    if (!o.diff.empty()) {
        auto diff = image::makeDiffImage(ia, ib);
        if (image::isError(diff) || image::isError(image::writePng(o.diff, std::get<image::Image>(diff)))) {
            std::fprintf(stderr, "obscura: cannot write the diff image %s\n", o.diff.c_str());
            return kExitBadInput;
        }
    }
    bool below = (o.psnrMin && !(m.psnr >= *o.psnrMin)) || (o.ssimMin && !(m.ssim >= *o.ssimMin));
    if (below) std::printf("below threshold\n");
    return below ? kExitBelowThreshold : kExitOk;
}

}  // namespace obscura::harness
