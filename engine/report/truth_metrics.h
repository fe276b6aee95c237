// vct against ground truth (vct compare --reference-dir): the light buffers of a vct render (`render --aux`)
// measured against a path-traced reference in the same units (`vct reference`), which also gives each pixel's
// surface id and the variance of each of its means. Pure functions on loaded images; the command
// (engine/app/cli/compare_command.cpp) reads the files, checks them with the *Problem functions and prints.
//
// Definitions (docs/truth_compare.md): lum = Rec.709 luminance (lib/color.glsl); "indirect" = final − direct
// (the indirect light leaving the surface); diffuse and specular are the demodulated incoming indirect
// radiance. Background = reference surface id −1; every metric is over the other pixels.
#pragma once

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/image_io.h"

namespace vct {

inline constexpr int kBackgroundSurface = -1;
inline constexpr double kTruthRelMseEpsilon = 1e-3;  // relMSE's (r² + ε)
inline constexpr double kLog2RatioEpsilon = 1e-4;    // log2((lum_vct + ε) / (lum_ref + ε))
inline constexpr double kLog2RatioRange = 2.0;       // the maps' colours span [−2, 2]
// Largest surface id accepted: ids are stored as float, exact up to 2^24.
inline constexpr int kMaxSurfaceId = 1 << 24;

// The four light buffers of one directory (linear HDR RGBA, row-major, top row first).
struct LightBuffers {
    ImageRgba32f finalImage, direct, diffuse, specular;
    // Only in a reference's variances, when it wrote indirect_variance.exr: the variance of its final −
    // direct estimated per sample. Empty otherwise: var_final + var_direct then bounds it.
    ImageRgba32f indirect;
};

// What `vct reference --out` writes.
struct TruthReference {
    LightBuffers mean;
    LightBuffers variance;             // per pixel and channel: the variance of the mean
    ImageRgba32f surfaceId;            // R: the surface id (an integer; −1 background)
    std::map<int, std::string> names;  // from reference.json; an id without a name is "surface N"
};

// The light quantities compared. Indirect = final − direct.
enum class Light { Final, Indirect, Diffuse, Specular, Direct };
const char* lightName(Light light);  // "final", "indirect", "diffuse", "specular", "direct"

// Σ lum over a set of pixels, vct's and the reference's, and the variance of the reference's sum.
struct LuminanceSums {
    double vct = 0.0, reference = 0.0;
    double referenceVariance = 0.0;  // Σ over pixels of Σ_c w_c² var_c
    // vct / reference; nothing when the reference's sum is 0 (or the quotient is not finite).
    std::optional<double> ratio() const;
    // sqrt(referenceVariance) / |reference|: the reference's own relative noise on its sum; nothing when 0.
    std::optional<double> referenceNoise() const;
};

struct RegionRatios {
    size_t pixels = 0;
    LuminanceSums indirect, diffuse, specular, direct;
};

struct SurfaceRatios {
    int id = 0;
    std::string name;
    RegionRatios sums;
};

// The image metrics of one light quantity over the non-background pixels.
struct TruthError {
    size_t samples = 0;     // non-background pixels × 3 channels
    double srgbMse = 0.0;   // on the tone-mapped sRGB image (peak 1)
    double relMse = 0.0;    // linear HDR, the reference's noise subtracted (may be < 0; see below)
    double relNoise = 0.0;  // mean var_r / (r² + ε): the part subtracted
    // 10·log10(1 / srgbMse); nothing when srgbMse is 0 (identical images: +∞) or there is no sample.
    std::optional<double> srgbPsnr() const;
    // The reference's own noise in srgbMse (compareWithTruth with a second reference): E[(T(v) − T(r))²] = (T(v) − E T(r))² + Var T(r),
    // and Var T(r) is measured against a second, independent reference. Nothing without one.
    std::optional<double> srgbReferenceNoise;
    // 10·log10(1 / srgbReferenceNoise): the reference's own PSNR against the truth it estimates.
    std::optional<double> referencePsnr() const;
    // 10·log10(1 / (srgbMse − srgbReferenceNoise)): vct's PSNR against the noise-free truth, estimated. Nothing
    // without a second reference, or when vct is within the reference's noise (the difference is ≤ 0).
    std::optional<double> srgbPsnrWithoutReferenceNoise() const;
};

struct TruthComparison {
    uint32_t width = 0, height = 0;
    size_t backgroundPixels = 0;
    float exposure = 1.0f;
    std::vector<SurfaceRatios> surfaces;  // by id; surfaces without pixels left out
    RegionRatios image;                   // all non-background pixels
    TruthError finalError, indirectError, diffuseError, specularError;
};

// First problem of an input image, or nothing: a NaN or Inf in R, G or B ("pixel (3, 7) G is NaN").
std::optional<std::string> nonFiniteProblem(const ImageRgba32f& image);
// As nonFiniteProblem, and also a negative value (a variance).
std::optional<std::string> varianceProblem(const ImageRgba32f& image);
// R not an integer in [−1, kMaxSurfaceId] ("pixel (0, 0) has surface id 0.5, not an integer >= -1").
std::optional<std::string> surfaceIdProblem(const ImageRgba32f& image);

// The reference's integer surface id at each pixel; throws vct::Error when surfaceIdProblem finds one.
std::vector<int> surfaceIds(const ImageRgba32f& surfaceIdImage);

// The comparison. Every image must have the reference's final size (throws vct::Error otherwise); values are
// assumed finite (the command checks). `exposure` is the tone map's (lib/color.glsl toneMapAces).
//
//  ratios:    Σ lum(vct) / Σ lum(ref) per surface and over the image, per quantity;
//  sRGB PSNR: 10 log10(1 / mean (T(v) − T(r))²), T(x) = linearToSrgb(toneMapAces(x, exposure)), the indirect
//             image clamped at 0 (T clamps negative values to 0 anyway);
//  relMSE:    mean over pixels and RGB of ((v − r)² − var_r) / (r² + ε), ε = 1e-3. E[(v − r)²] = (v − μ)² +
//             var_r for the reference mean r of the true value μ, so this estimates vct's own error without
//             the reference's noise: unbiased, hence negative when vct is within the noise (−relNoise when
//             v = r exactly). relMse + relNoise is the plain relative MSE. The variance of the indirect
//             image I = F − D is taken as var_F + var_D, an upper bound: Var(F − D) = Var F + Var D −
//             2 Cov(F, D) and Cov(F, D) = Var D + Cov(I, D) ≥ 0 unless the reference's indirect estimate
//             is strongly anti-correlated with its direct one (independent ones: over by 2 var_D).
//  With `second`, another path-traced estimate of the same frame with independent samples (`vct reference
//  --seed`, any spp), also the reference's own noise in each sRGB MSE. With d = T(v) − T(r) and
//  d₂ = T(v) − T(r₂) per pixel and channel, independent noise in r and r₂ and E T(r) = E T(r₂) = μ:
//    E[d·d₂] = (T(v) − μ)²  (vct's own error, the noise cancels),   E[d² − d·d₂] = Var T(r),
//  so srgbReferenceNoise = mean (d² − d·d₂) over the same pixels and srgbPsnrWithoutReferenceNoise is
//  10 log10(1 / mean d·d₂). No assumption on how the noise scales with spp (cornell's 1024- and 4096-spp
//  references differ by 20 % more than 1/spp predicts: the noise is heavy-tailed). This, not the per-pixel
//  variances the reference writes (two halves of its samples, linear), is what the sRGB MSE holds of the
//  reference's noise: cornell's 1024-spp references of two seeds differ by 22.0 dB of indirect sRGB PSNR
//  (docs/truth_compare.md). `second` of another size throws too ("second reference final is …").
TruthComparison compareWithTruth(const TruthReference& reference, const LightBuffers& vct, float exposure,
                                 const LightBuffers* second = nullptr);

// log2((max(lum_vct, 0) + ε) / (max(lum_ref, 0) + ε)) per pixel (ε = 1e-4, unclamped), 0 on the background;
// width × height values, top row first. Light::Final and Light::Direct work too.
std::vector<float> log2RatioMap(const TruthReference& reference, const LightBuffers& vct, Light light);
// The map drawn with a diverging colour map: blue at −2, white at 0, red at +2 (clamped), black background.
ImageRgba8 log2RatioPng(const std::vector<float>& values, const std::vector<int>& ids, uint32_t width,
                        uint32_t height);
// The map as RGBA32F: R = G = B = the value (background 0), A = 1.
std::vector<float> log2RatioRgba(const std::vector<float>& values);

// `compare --reference-dir`'s output (schema in docs/truth_compare.md). JSON has no infinity or NaN: a PSNR
// of identical images, a ratio or noise whose denominator is 0 and any error over no pixel are null.
nlohmann::json truthJson(const TruthComparison& comparison);
std::string formatTruthTable(const TruthComparison& comparison);

}  // namespace vct
