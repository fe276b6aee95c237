#include "io/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"

namespace vct {

ImageError compareImages(const ImageRgba32f& reference, const ImageRgba32f& image) {
    if (reference.width != image.width || reference.height != image.height)
        throw Error("images differ in size: " + std::to_string(reference.width) + "x" +
                    std::to_string(reference.height) + " vs " + std::to_string(image.width) + "x" +
                    std::to_string(image.height));
    constexpr double kRelEpsilon = 0.01;
    ImageError error;
    double sum = 0.0, relSum = 0.0, peak = 0.0;
    size_t count = 0;
    const size_t pixels = size_t(reference.width) * reference.height;
    for (size_t i = 0; i < pixels; ++i) {
        for (size_t c = 0; c < 3; ++c) {
            const double r = reference.pixels[i * 4 + c], x = image.pixels[i * 4 + c];
            if (!std::isfinite(x) || !std::isfinite(r)) {
                ++error.nonFinite;
                continue;
            }
            const double d = x - r;
            sum += d * d;
            relSum += d * d / (r * r + kRelEpsilon);
            peak = std::max(peak, r);
            error.maxAbs = std::max(error.maxAbs, std::abs(d));
            ++count;
        }
    }
    error.mse = count ? sum / double(count) : 0.0;
    error.relMse = count ? relSum / double(count) : 0.0;
    error.psnr = error.mse > 0.0 ? 10.0 * std::log10(std::max(peak, 1e-12) * std::max(peak, 1e-12) / error.mse)
                                 : std::numeric_limits<double>::infinity();
    return error;
}

std::string formatImageError(const ImageError& e) {
    char line[200];
    std::snprintf(line, sizeof(line), "mse %.6g  rel_mse %.6g  psnr %.2f dB  max %.4g%s", e.mse, e.relMse, e.psnr,
                  e.maxAbs, e.nonFinite ? "  NON-FINITE VALUES" : "");
    return line;
}

}  // namespace vct
