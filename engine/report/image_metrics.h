// Error metrics on linear HDR images (docs/design.md §8.2): how far an image is from a reference computed in the
// same run. Over the RGB channels of every pixel (alpha ignored).
#pragma once

#include <string>

#include "io/image_io.h"

namespace vct {

struct ImageError {
    double mse = 0.0;  // mean over pixels and RGB of (x − r)²
    double relMse =
        0.0;  // mean of (x − r)² / (r² + ε), ε = 0.01: error relative to the signal, dark pixels bounded
    double psnr = 0.0;  // 10·log10(peak² / MSE) with peak the reference's largest RGB value (∞ when equal)
    double maxAbs = 0.0;   // largest |x − r|
    size_t nonFinite = 0;  // NaN or Inf values in the image (each counts; they are left out of the sums)
};

// Throws vct::Error when the sizes differ. `peak` sets the PSNR's peak value; 0: the reference's largest
// value (right for demodulated indirect light; wrong for a final HDR image, whose peak is a light source).
ImageError compareImages(const ImageRgba32f& reference, const ImageRgba32f& image, double peak = 0.0);

// The display image of a linear HDR one, as the composite pass makes it (lib/color.glsl): exposure, ACES tone
// map, sRGB encoding, in [0, 1] (not quantised to 8 bits).
ImageRgba32f toneMappedSrgb(const ImageRgba32f& hdr, float exposure);

// Errors of two final HDR images as seen on the display: tone-mapped sRGB, PSNR with peak 1.
ImageError compareToneMapped(const ImageRgba32f& reference, const ImageRgba32f& image, float exposure);

// A heat map of |image − reference| (mean over RGB) for error strips: black 0, through red and yellow to
// white at `fullScale` and above; RGBA8, the images' size.
ImageRgba8 errorHeatMap(const ImageRgba32f& reference, const ImageRgba32f& image, double fullScale);

// One line: "mse 1.2e-4  rel_mse 3.4e-3  psnr 38.2 dB  max 0.5".
std::string formatImageError(const ImageError& error);

}  // namespace vct
