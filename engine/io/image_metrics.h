// Error metrics on linear HDR images (DESIGN §5): how far an image is from a reference computed in the same
// run. Over the RGB channels of every pixel (alpha ignored).
#pragma once

#include <string>

#include "io/image_io.h"

namespace vct {

struct ImageError {
    double mse = 0.0;     // mean over pixels and RGB of (x − r)²
    double relMse = 0.0;  // mean of (x − r)² / (r² + ε), ε = 0.01: error relative to the signal, dark pixels bounded
    double psnr = 0.0;    // 10·log10(peak² / MSE) with peak the reference's largest RGB value (∞ when equal)
    double maxAbs = 0.0;  // largest |x − r|
    size_t nonFinite = 0; // NaN or Inf values in the image (each counts; they are left out of the sums)
};

// Throws vct::Error when the sizes differ.
ImageError compareImages(const ImageRgba32f& reference, const ImageRgba32f& image);

// One line: "mse 1.2e-4  rel_mse 3.4e-3  psnr 38.2 dB  max 0.5".
std::string formatImageError(const ImageError& error);

}  // namespace vct
