#include "report/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "render/shader_math.h"

namespace vct {

namespace {

void checkSameSize(const ImageRgba32f& reference, const ImageRgba32f& image) {
    if (reference.width != image.width || reference.height != image.height)
        throw Error("images differ in size: " + std::to_string(reference.width) + "x" +
                    std::to_string(reference.height) + " vs " + std::to_string(image.width) + "x" +
                    std::to_string(image.height));
}

}  // namespace

ImageError compareImages(const ImageRgba32f& reference, const ImageRgba32f& image, double peakValue) {
    checkSameSize(reference, image);
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
    if (peakValue > 0.0) peak = peakValue;
    error.psnr = error.mse > 0.0
                     ? 10.0 * std::log10(std::max(peak, 1e-12) * std::max(peak, 1e-12) / error.mse)
                     : std::numeric_limits<double>::infinity();
    return error;
}

ImageRgba32f toneMappedSrgb(const ImageRgba32f& hdr, float exposure) {
    ImageRgba32f out{hdr.width, hdr.height, hdr.pixels};
    for (size_t i = 0; i + 3 < out.pixels.size(); i += 4) {
        const glm::vec3 c(hdr.pixels[i], hdr.pixels[i + 1], hdr.pixels[i + 2]);
        // Non-finite values stay so (compareImages counts them) rather than being clamped into range.
        if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b)) continue;
        const glm::vec3 display = glsl::linearToSrgb(glsl::toneMapAces(c, exposure));
        for (int k = 0; k < 3; ++k) out.pixels[i + size_t(k)] = display[k];
    }
    return out;
}

ImageError compareToneMapped(const ImageRgba32f& reference, const ImageRgba32f& image, float exposure) {
    checkSameSize(reference, image);
    return compareImages(toneMappedSrgb(reference, exposure), toneMappedSrgb(image, exposure), 1.0);
}

ImageRgba8 errorHeatMap(const ImageRgba32f& reference, const ImageRgba32f& image, double fullScale) {
    checkSameSize(reference, image);
    ImageRgba8 map{reference.width, reference.height, std::vector<uint8_t>(reference.pixels.size())};
    for (size_t i = 0; i + 3 < map.pixels.size(); i += 4) {
        double sum = 0.0;
        for (size_t c = 0; c < 3; ++c)
            sum += std::abs(double(image.pixels[i + c]) - double(reference.pixels[i + c]));
        // Non-finite differences show as full scale, never as 0.
        const double t =
            std::isfinite(sum) ? std::clamp(sum / 3.0 / std::max(fullScale, 1e-30), 0.0, 1.0) : 1.0;
        // Black → red → yellow → white, each a third of the scale.
        const double rgb[3] = {std::clamp(3.0 * t, 0.0, 1.0), std::clamp(3.0 * t - 1.0, 0.0, 1.0),
                               std::clamp(3.0 * t - 2.0, 0.0, 1.0)};
        for (size_t c = 0; c < 3; ++c) map.pixels[i + c] = uint8_t(std::lround(255.0 * rgb[c]));
        map.pixels[i + 3] = 255;
    }
    return map;
}

std::string formatImageError(const ImageError& e) {
    char line[200];
    std::snprintf(line, sizeof(line), "mse %.6g  rel_mse %.6g  psnr %.2f dB  max %.4g%s", e.mse, e.relMse,
                  e.psnr, e.maxAbs, e.nonFinite ? "  NON-FINITE VALUES" : "");
    return line;
}

}  // namespace vct
