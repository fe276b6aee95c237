#include "report/truth_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "render/shader_math.h"
#include "report/image_metrics.h"
#include "scene/input_limits.h"

namespace vct {

namespace {

constexpr const char* kChannelNames[3] = {"R", "G", "B"};

// The Rec.709 weights of lib/color.glsl's luminance, taken from the function itself.
const glm::dvec3& luminanceWeights() {
    static const glm::dvec3 weights(glsl::luminance(glm::vec3(1.0f, 0.0f, 0.0f)),
                                    glsl::luminance(glm::vec3(0.0f, 1.0f, 0.0f)),
                                    glsl::luminance(glm::vec3(0.0f, 0.0f, 1.0f)));
    return weights;
}

double lum(const glm::dvec3& c) {
    return glm::dot(c, luminanceWeights());
}
// Variance of the luminance of a pixel whose channels have variances v (independent): Σ_c w_c² v_c.
double lumVariance(const glm::dvec3& v) {
    const glm::dvec3& w = luminanceWeights();
    return glm::dot(w * w, v);
}

glm::dvec3 rgb(const ImageRgba32f& image, size_t pixel) {
    const float* p = image.pixels.data() + pixel * 4;
    return {p[0], p[1], p[2]};
}

glm::dvec3 value(const LightBuffers& buffers, Light light, size_t pixel) {
    switch (light) {
        case Light::Final:
            return rgb(buffers.finalImage, pixel);
        case Light::Indirect:
            return rgb(buffers.finalImage, pixel) - rgb(buffers.direct, pixel);
        case Light::Diffuse:
            return rgb(buffers.diffuse, pixel);
        case Light::Specular:
            return rgb(buffers.specular, pixel);
        case Light::Direct:
            return rgb(buffers.direct, pixel);
    }
    return {};
}

// The variance of the reference's Indirect (final − direct): its own estimate when the reference wrote one,
// else var_final + var_direct, an upper bound (see compareWithTruth in the header).
glm::dvec3 variance(const LightBuffers& variances, Light light, size_t pixel) {
    if (light == Light::Indirect && !variances.indirect.pixels.empty()) return rgb(variances.indirect, pixel);
    if (light == Light::Indirect) return rgb(variances.finalImage, pixel) + rgb(variances.direct, pixel);
    return value(variances, light, pixel);
}

void checkSize(const ImageRgba32f& image, const std::string& what, uint32_t width, uint32_t height) {
    if (image.width != width || image.height != height || image.pixels.size() != size_t(width) * height * 4)
        throw Error(what + " is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    ", the reference's final " + std::to_string(width) + "x" + std::to_string(height));
}

std::string pixelText(const ImageRgba32f& image, size_t pixel) {
    return "pixel (" + std::to_string(pixel % image.width) + ", " + std::to_string(pixel / image.width) + ")";
}

std::optional<std::string> channelProblem(const ImageRgba32f& image, bool negativeToo) {
    const size_t pixels = size_t(image.width) * image.height;
    for (size_t i = 0; i < pixels && i * 4 + 3 < image.pixels.size(); ++i) {
        for (size_t c = 0; c < 3; ++c) {
            const float v = image.pixels[i * 4 + c];
            if (std::isnan(v)) return pixelText(image, i) + " " + kChannelNames[c] + " is NaN";
            if (std::isinf(v)) return pixelText(image, i) + " " + kChannelNames[c] + " is infinite";
            if (negativeToo && v < 0.0f)
                return pixelText(image, i) + " " + kChannelNames[c] + " is negative (" + numberText(v) + ")";
        }
    }
    return std::nullopt;
}

// The display image of an RGB quantity, as the composite pass makes it (negative values become 0).
ImageRgba32f displayImage(const LightBuffers& buffers, Light light, float exposure) {
    const ImageRgba32f& shape = buffers.finalImage;
    ImageRgba32f linear{shape.width, shape.height, std::vector<float>(shape.pixels.size(), 1.0f)};
    const size_t pixels = size_t(shape.width) * shape.height;
    for (size_t i = 0; i < pixels; ++i) {
        const glm::dvec3 c = glm::max(value(buffers, light, i), glm::dvec3(0.0));
        for (size_t k = 0; k < 3; ++k) linear.pixels[i * 4 + k] = float(c[int(k)]);
    }
    return toneMappedSrgb(linear, exposure);
}

// mean (T(v) − T(a))·(T(v) − T(b)) over the non-background pixels and RGB of images tone-mapped for display:
// the sRGB MSE of v against a when b is a, and with b a second reference vct's error without the noise
// (compareWithTruth).
double srgbCrossOver(const std::vector<int>& ids, const ImageRgba32f& shownV, const ImageRgba32f& shownA,
                     const ImageRgba32f& shownB) {
    double sum = 0.0;
    size_t samples = 0;
    for (size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] == kBackgroundSurface) continue;
        const glm::dvec3 v = rgb(shownV, i);
        sum += glm::dot(v - rgb(shownA, i), v - rgb(shownB, i));
        samples += 3;
    }
    return samples > 0 ? sum / double(samples) : 0.0;
}

TruthError measure(const TruthReference& reference, const LightBuffers& vct, const LightBuffers* second,
                   Light light, const std::vector<int>& ids, float exposure) {
    const ImageRgba32f shownReference = displayImage(reference.mean, light, exposure);
    const ImageRgba32f shownVct = displayImage(vct, light, exposure);
    TruthError error;
    double relSum = 0.0, noiseSum = 0.0;
    for (size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] == kBackgroundSurface) continue;
        const glm::dvec3 r = value(reference.mean, light, i), v = value(vct, light, i);
        const glm::dvec3 var = variance(reference.variance, light, i);
        for (int c = 0; c < 3; ++c) {
            const double d = v[c] - r[c], denominator = r[c] * r[c] + kTruthRelMseEpsilon;
            relSum += (d * d - var[c]) / denominator;
            noiseSum += var[c] / denominator;
        }
        error.samples += 3;
    }
    if (error.samples > 0) {
        const double n = double(error.samples);
        error.srgbMse = srgbCrossOver(ids, shownVct, shownReference, shownReference);
        if (second)
            error.srgbReferenceNoise = error.srgbMse - srgbCrossOver(ids, shownVct, shownReference,
                                                                     displayImage(*second, light, exposure));
        error.relMse = relSum / n;
        error.relNoise = noiseSum / n;
    }
    return error;
}

void accumulate(RegionRatios& region, const TruthReference& reference, const LightBuffers& vct, size_t i) {
    ++region.pixels;
    const std::pair<LuminanceSums*, Light> quantities[4] = {{&region.indirect, Light::Indirect},
                                                            {&region.diffuse, Light::Diffuse},
                                                            {&region.specular, Light::Specular},
                                                            {&region.direct, Light::Direct}};
    for (const auto& [sums, light] : quantities) {
        sums->vct += lum(value(vct, light, i));
        sums->reference += lum(value(reference.mean, light, i));
        sums->referenceVariance += lumVariance(variance(reference.variance, light, i));
    }
}

nlohmann::json optionalJson(const std::optional<double>& value) {
    return value && std::isfinite(*value) ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

nlohmann::json sumsJson(const LuminanceSums& sums) {
    return {{"ratio", optionalJson(sums.ratio())},
            {"vct_sum", sums.vct},
            {"reference_sum", sums.reference},
            {"reference_noise", optionalJson(sums.referenceNoise())}};
}

nlohmann::json regionJson(const RegionRatios& region) {
    return {{"pixels", region.pixels},
            {"indirect", sumsJson(region.indirect)},
            {"diffuse", sumsJson(region.diffuse)},
            {"specular", sumsJson(region.specular)},
            {"direct", sumsJson(region.direct)}};
}

nlohmann::json errorJson(const TruthError& error) {
    const bool any = error.samples > 0;
    auto number = [&](double v) { return optionalJson(any ? std::optional<double>(v) : std::nullopt); };
    return {{"psnr_srgb", optionalJson(error.srgbPsnr())},
            {"mse_srgb", number(error.srgbMse)},
            {"mse_srgb_reference_noise", optionalJson(any ? error.srgbReferenceNoise : std::nullopt)},
            {"psnr_srgb_reference", optionalJson(error.referencePsnr())},
            {"psnr_srgb_without_reference_noise", optionalJson(error.srgbPsnrWithoutReferenceNoise())},
            {"rel_mse", number(error.relMse)},
            {"rel_mse_noise", number(error.relNoise)},
            {"rel_mse_raw", number(error.relMse + error.relNoise)}};
}

std::string ratioText(const std::optional<double>& value) {
    char text[32];
    if (!value) return "-";
    std::snprintf(text, sizeof(text), "%.3f", *value);
    return text;
}

std::string percentText(const std::optional<double>& value) {
    char text[32];
    if (!value) return "-";
    std::snprintf(text, sizeof(text), "%.2f%%", 100.0 * *value);
    return text;
}

std::string regionLine(const std::string& label, const RegionRatios& region) {
    char line[256];
    std::snprintf(line, sizeof(line), "%-28.28s %8zu %9s %9s %9s %9s %9s %9s %9s\n", label.c_str(),
                  region.pixels, ratioText(region.indirect.ratio()).c_str(),
                  ratioText(region.diffuse.ratio()).c_str(), ratioText(region.specular.ratio()).c_str(),
                  ratioText(region.direct.ratio()).c_str(),
                  percentText(region.indirect.referenceNoise()).c_str(),
                  percentText(region.diffuse.referenceNoise()).c_str(),
                  percentText(region.specular.referenceNoise()).c_str());
    return line;
}

// Every image of both directories at the reference's final size (throws naming the first that is not).
void checkSizes(const TruthReference& reference, const LightBuffers& vct) {
    const uint32_t w = reference.mean.finalImage.width, h = reference.mean.finalImage.height;
    const std::pair<const ImageRgba32f*, const char*> images[] = {
        {&reference.mean.finalImage, "reference final"},
        {&reference.mean.direct, "reference direct"},
        {&reference.mean.diffuse, "reference diffuse_indirect"},
        {&reference.mean.specular, "reference specular_indirect"},
        {&reference.variance.finalImage, "reference final_variance"},
        {&reference.variance.direct, "reference direct_variance"},
        {&reference.variance.diffuse, "reference diffuse_indirect_variance"},
        {&reference.variance.specular, "reference specular_indirect_variance"},
        {&reference.surfaceId, "reference surface_id"},
        {&vct.finalImage, "vct final"},
        {&vct.direct, "vct direct"},
        {&vct.diffuse, "vct diffuse_indirect"},
        {&vct.specular, "vct specular_indirect"}};
    for (const auto& [image, what] : images) checkSize(*image, what, w, h);
}

}  // namespace

const char* lightName(Light light) {
    switch (light) {
        case Light::Final:
            return "final";
        case Light::Indirect:
            return "indirect";
        case Light::Diffuse:
            return "diffuse";
        case Light::Specular:
            return "specular";
        case Light::Direct:
            return "direct";
    }
    return "?";
}

std::optional<double> LuminanceSums::ratio() const {
    if (reference == 0.0) return std::nullopt;
    const double r = vct / reference;
    return std::isfinite(r) ? std::optional<double>(r) : std::nullopt;
}

std::optional<double> LuminanceSums::referenceNoise() const {
    if (reference == 0.0) return std::nullopt;
    const double n = std::sqrt(referenceVariance) / std::abs(reference);
    return std::isfinite(n) ? std::optional<double>(n) : std::nullopt;
}

std::optional<double> TruthError::srgbPsnr() const {
    if (samples == 0 || !(srgbMse > 0.0)) return std::nullopt;
    return 10.0 * std::log10(1.0 / srgbMse);
}

std::optional<double> TruthError::referencePsnr() const {
    if (samples == 0 || !srgbReferenceNoise || !(*srgbReferenceNoise > 0.0)) return std::nullopt;
    return 10.0 * std::log10(1.0 / *srgbReferenceNoise);
}

std::optional<double> TruthError::srgbPsnrWithoutReferenceNoise() const {
    if (samples == 0 || !srgbReferenceNoise) return std::nullopt;
    const double mse = srgbMse - *srgbReferenceNoise;
    if (!(mse > 0.0)) return std::nullopt;
    return 10.0 * std::log10(1.0 / mse);
}

std::optional<std::string> nonFiniteProblem(const ImageRgba32f& image) {
    return channelProblem(image, false);
}

std::optional<std::string> varianceProblem(const ImageRgba32f& image) {
    return channelProblem(image, true);
}

std::optional<std::string> surfaceIdProblem(const ImageRgba32f& image) {
    const size_t pixels = size_t(image.width) * image.height;
    for (size_t i = 0; i < pixels && i * 4 < image.pixels.size(); ++i) {
        const float v = image.pixels[i * 4];
        if (!(v >= float(kBackgroundSurface) && v <= float(kMaxSurfaceId) && v == std::floor(v)))
            return pixelText(image, i) + " has surface id " + numberText(v) + ", not an integer from -1 to " +
                   std::to_string(kMaxSurfaceId);
    }
    return std::nullopt;
}

std::vector<int> surfaceIds(const ImageRgba32f& surfaceIdImage) {
    if (auto problem = surfaceIdProblem(surfaceIdImage)) throw Error("reference surface_id: " + *problem);
    std::vector<int> ids(size_t(surfaceIdImage.width) * surfaceIdImage.height);
    for (size_t i = 0; i < ids.size(); ++i) ids[i] = int(surfaceIdImage.pixels[i * 4]);
    return ids;
}

TruthComparison compareWithTruth(const TruthReference& reference, const LightBuffers& vct, float exposure,
                                 const LightBuffers* second) {
    checkSizes(reference, vct);
    const uint32_t w = reference.mean.finalImage.width, h = reference.mean.finalImage.height;
    if (second) {
        const std::pair<const ImageRgba32f*, const char*> images[] = {
            {&second->finalImage, "second reference final"},
            {&second->direct, "second reference direct"},
            {&second->diffuse, "second reference diffuse"},
            {&second->specular, "second reference specular"}};
        for (const auto& [image, what] : images) checkSize(*image, what, w, h);
    }
    TruthComparison result;
    result.width = w;
    result.height = h;
    result.exposure = exposure;
    const std::vector<int> ids = surfaceIds(reference.surfaceId);
    std::map<int, RegionRatios> bySurface;
    for (size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] == kBackgroundSurface) {
            ++result.backgroundPixels;
            continue;
        }
        accumulate(bySurface[ids[i]], reference, vct, i);
        accumulate(result.image, reference, vct, i);
    }
    for (const auto& [id, sums] : bySurface) {
        const auto named = reference.names.find(id);
        result.surfaces.push_back(
            {id, named != reference.names.end() ? named->second : "surface " + std::to_string(id), sums});
    }
    result.finalError = measure(reference, vct, second, Light::Final, ids, exposure);
    result.indirectError = measure(reference, vct, second, Light::Indirect, ids, exposure);
    result.diffuseError = measure(reference, vct, second, Light::Diffuse, ids, exposure);
    result.specularError = measure(reference, vct, second, Light::Specular, ids, exposure);
    return result;
}

std::vector<float> log2RatioMap(const TruthReference& reference, const LightBuffers& vct, Light light) {
    checkSizes(reference, vct);
    const std::vector<int> ids = surfaceIds(reference.surfaceId);
    std::vector<float> values(ids.size(), 0.0f);
    for (size_t i = 0; i < ids.size(); ++i) {
        if (ids[i] == kBackgroundSurface) continue;
        const double v = std::max(lum(value(vct, light, i)), 0.0);
        const double r = std::max(lum(value(reference.mean, light, i)), 0.0);
        values[i] = float(std::log2((v + kLog2RatioEpsilon) / (r + kLog2RatioEpsilon)));
    }
    return values;
}

ImageRgba8 log2RatioPng(const std::vector<float>& values, const std::vector<int>& ids, uint32_t width,
                        uint32_t height) {
    if (values.size() != size_t(width) * height || ids.size() != values.size())
        throw Error("log2 ratio map: " + std::to_string(values.size()) + " values for a " +
                    std::to_string(width) + "x" + std::to_string(height) + " image");
    ImageRgba8 png{width, height, std::vector<uint8_t>(values.size() * 4, 0)};
    for (size_t i = 0; i < values.size(); ++i) {
        uint8_t* p = png.pixels.data() + i * 4;
        p[3] = 255;
        if (ids[i] == kBackgroundSurface) continue;  // black
        // Blue (−range) → white (0) → red (+range), linear in each half.
        const double t =
            std::isfinite(values[i]) ? std::clamp(double(values[i]) / kLog2RatioRange, -1.0, 1.0) : 0.0;
        const double fade = 1.0 - std::abs(t);
        const double r = t < 0.0 ? fade : 1.0, g = fade, b = t > 0.0 ? fade : 1.0;
        p[0] = uint8_t(std::lround(255.0 * r));
        p[1] = uint8_t(std::lround(255.0 * g));
        p[2] = uint8_t(std::lround(255.0 * b));
    }
    return png;
}

std::vector<float> log2RatioRgba(const std::vector<float>& values) {
    std::vector<float> rgba(values.size() * 4, 1.0f);
    for (size_t i = 0; i < values.size(); ++i) rgba[i * 4] = rgba[i * 4 + 1] = rgba[i * 4 + 2] = values[i];
    return rgba;
}

nlohmann::json truthJson(const TruthComparison& comparison) {
    nlohmann::json surfaces = nlohmann::json::array();
    for (const SurfaceRatios& surface : comparison.surfaces) {
        nlohmann::json entry = regionJson(surface.sums);
        entry["id"] = surface.id;
        entry["name"] = surface.name;
        surfaces.push_back(std::move(entry));
    }
    return {{"width", comparison.width},
            {"height", comparison.height},
            {"pixels", comparison.image.pixels},
            {"background_pixels", comparison.backgroundPixels},
            {"exposure", comparison.exposure},
            {"surfaces", std::move(surfaces)},
            {"image", regionJson(comparison.image)},
            {"errors",
             {{"final", errorJson(comparison.finalError)},
              {"indirect", errorJson(comparison.indirectError)},
              {"diffuse", errorJson(comparison.diffuseError)},
              {"specular", errorJson(comparison.specularError)}}}};
}

std::string formatTruthTable(const TruthComparison& c) {
    std::string text;
    char line[256];
    std::snprintf(
        line, sizeof(line),
        "%ux%u: %zu pixels on surfaces, %zu background; ratios = sum lum(vct) / sum lum(reference)\n",
        c.width, c.height, c.image.pixels, c.backgroundPixels);
    text += line;
    std::snprintf(line, sizeof(line), "%-28s %8s %9s %9s %9s %9s %9s %9s %9s\n", "surface", "pixels",
                  "indirect", "diffuse", "specular", "direct", "noise:ind", "noise:dif", "noise:spe");
    text += line;
    for (const SurfaceRatios& surface : c.surfaces)
        text += regionLine(std::to_string(surface.id) + " " + surface.name, surface.sums);
    text += regionLine("whole image", c.image);
    text += "(noise:*: the reference's own relative noise on its sum, sqrt(sum var lum) / sum lum)\n";
    std::snprintf(line, sizeof(line), "\n%-10s %12s %12s %14s %14s %14s\n", "light", "sRGB PSNR", "sRGB MSE",
                  "relMSE", "ref.noise", "relMSE raw");
    text += line;
    const std::pair<const char*, const TruthError*> errors[] = {{"final", &c.finalError},
                                                                {"indirect", &c.indirectError},
                                                                {"diffuse", &c.diffuseError},
                                                                {"specular", &c.specularError}};
    for (const auto& [name, error] : errors) {
        if (error->samples == 0) {
            std::snprintf(line, sizeof(line), "%-10s %12s\n", name, "no pixels");
        } else {
            const std::optional<double> psnr = error->srgbPsnr();
            char psnrText[32];
            if (psnr)
                std::snprintf(psnrText, sizeof(psnrText), "%.2f dB", *psnr);
            else
                std::snprintf(psnrText, sizeof(psnrText), "inf");
            std::snprintf(line, sizeof(line), "%-10s %12s %12.4g %14.4g %14.4g %14.4g\n", name, psnrText,
                          error->srgbMse, error->relMse, error->relNoise, error->relMse + error->relNoise);
        }
        text += line;
    }
    std::snprintf(
        line, sizeof(line),
        "(sRGB: exposure %g, ACES, sRGB, peak 1; relMSE: linear HDR, mean ((v - r)^2 - var r) / (r^2 + %g), "
        "the reference's noise subtracted; ref.noise: mean var r / (r^2 + eps))\n",
        double(c.exposure), kTruthRelMseEpsilon);
    text += line;
    if (!c.finalError.srgbReferenceNoise) return text;
    auto dbText = [](const std::optional<double>& db, const char* none) {
        char t[32];
        if (db)
            std::snprintf(t, sizeof(t), "%.2f dB", *db);
        else
            std::snprintf(t, sizeof(t), "%s", none);
        return std::string(t);
    };
    std::snprintf(line, sizeof(line), "\n%-10s %16s %16s %26s\n", "light", "ref. noise MSE", "ref. PSNR",
                  "PSNR without ref. noise");
    text += line;
    for (const auto& [name, error] : errors) {
        if (error->samples == 0 || !error->srgbReferenceNoise) continue;
        std::snprintf(line, sizeof(line), "%-10s %16.4g %16s %26s\n", name, *error->srgbReferenceNoise,
                      dbText(error->referencePsnr(), "-").c_str(),
                      dbText(error->srgbPsnrWithoutReferenceNoise(), "within the noise").c_str());
        text += line;
    }
    text +=
        "(from a second reference of the same frame with other samples: mean (T(v) - T(r))(T(v) - T(r2)) is "
        "the error without the reference's noise; the sRGB MSE above includes that noise)\n";
    return text;
}

}  // namespace vct
