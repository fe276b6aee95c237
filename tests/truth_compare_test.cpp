// vct against ground truth (`vct compare --reference-dir`, engine/report/truth_metrics.h) on synthetic reference
// and vct directories whose answers are known exactly: per-surface ratios, the reference's noise on its sums,
// relMSE with the noise subtracted, PSNR of identical images (null in JSON: it has no infinity), a
// background-only image (null ratios, never NaN), log2 ratio maps, and one-line errors for missing files,
// size mismatches, NaN and bad usage. CPU only: no Vulkan device is needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/image_io.h"
#include "report/image_metrics.h"
#include "report/truth_metrics.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using vct::ImageRgba32f;
using vct::LightBuffers;
using vct::TruthReference;
using Rgb = std::array<float, 3>;

// The synthetic frame: 8x4 pixels, columns 0-3 surface 0, 4-6 surface 1, 7 background.
constexpr uint32_t kWidth = 8, kHeight = 4;
int surfaceAt(uint32_t x, uint32_t) {
    return x < 4 ? 0 : x < 7 ? 1 : -1;
}

ImageRgba32f makeImage(const std::function<Rgb(uint32_t, uint32_t)>& f, uint32_t w = kWidth,
                       uint32_t h = kHeight) {
    ImageRgba32f image{w, h, std::vector<float>(size_t(w) * h * 4, 1.0f)};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const Rgb c = f(x, y);
            for (size_t k = 0; k < 3; ++k) image.pixels[(size_t(y) * w + x) * 4 + k] = c[k];
        }
    return image;
}

// The reference's light, varying over the frame. final = direct + indirect.
Rgb refDirect(uint32_t x, uint32_t y) {
    return {0.5f + 0.1f * float(x), 0.4f, 0.3f + 0.05f * float(y)};
}
Rgb refIndirect(uint32_t x, uint32_t y) {
    return {0.125f + 0.0625f * float(x), 0.25f, 0.0625f * float(y + 1)};
}
Rgb refDiffuse(uint32_t x, uint32_t) {
    return {0.2f, 0.3f + 0.01f * float(x), 0.1f};
}
Rgb refSpecular(uint32_t, uint32_t y) {
    return {0.05f + 0.01f * float(y), 0.02f, 0.03f};
}
Rgb refFinal(uint32_t x, uint32_t y) {
    const Rgb d = refDirect(x, y), i = refIndirect(x, y);
    return {d[0] + i[0], d[1] + i[1], d[2] + i[2]};
}
// Per-channel variance of each mean (constant).
constexpr float kVarFinal = 1e-4f, kVarDirect = 2e-4f, kVarDiffuse = 3e-4f, kVarSpecular = 4e-4f;

Rgb scaled(Rgb c, float k) {
    return {c[0] * k, c[1] * k, c[2] * k};
}

TruthReference makeReference(const std::function<int(uint32_t, uint32_t)>& surface = surfaceAt) {
    TruthReference r;
    r.mean = {makeImage(refFinal), makeImage(refDirect), makeImage(refDiffuse), makeImage(refSpecular)};
    auto constant = [](float v) { return makeImage([v](uint32_t, uint32_t) { return Rgb{v, v, v}; }); };
    r.variance = {constant(kVarFinal), constant(kVarDirect), constant(kVarDiffuse), constant(kVarSpecular)};
    r.surfaceId = makeImage([&](uint32_t x, uint32_t y) {
        const float id = float(surface(x, y));
        return Rgb{id, 0.0f, 0.0f};
    });
    r.names = {{0, "room/red"}, {1, "room/green"}, {5, "unused"}};
    return r;
}

// vct: the reference's light × 2 on surface 0, × 1 on surface 1, × 7 on the background (must not count).
float vctFactor(uint32_t x, uint32_t y) {
    return surfaceAt(x, y) == 0 ? 2.0f : surfaceAt(x, y) == 1 ? 1.0f : 7.0f;
}

LightBuffers makeScaledVct() {
    auto scale = [](Rgb (*f)(uint32_t, uint32_t)) {
        return makeImage([f](uint32_t x, uint32_t y) { return scaled(f(x, y), vctFactor(x, y)); });
    };
    return {scale(refFinal), scale(refDirect), scale(refDiffuse), scale(refSpecular)};
}

double lum(Rgb c) {
    return vct::test::luminance(c[0], c[1], c[2]);
}

// Σ lum of f over the pixels of `surface` (−2: every non-background pixel), times vct's factor when asked.
double sumLum(Rgb (*f)(uint32_t, uint32_t), int surface, bool vctScaled) {
    double sum = 0.0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const int s = surfaceAt(x, y);
            if (s == -1 || (surface != -2 && s != surface)) continue;
            sum += lum(f(x, y)) * (vctScaled ? vctFactor(x, y) : 1.0);
        }
    return sum;
}

void writeDir(const fs::path& dir, const LightBuffers& light, const std::string& suffix = "") {
    const std::pair<const ImageRgba32f*, const char*> files[] = {{&light.finalImage, "final"},
                                                                 {&light.direct, "direct"},
                                                                 {&light.diffuse, "diffuse_indirect"},
                                                                 {&light.specular, "specular_indirect"}};
    for (const auto& [image, name] : files)
        vct::writeExr(dir / (std::string(name) + suffix + ".exr"), image->width, image->height,
                      image->pixels);
}

// `extra`: more reference.json members, each followed by a comma (e.g. R"("seed": 2, )").
void writeReferenceDir(const fs::path& dir, const TruthReference& r, const std::string& extra = "") {
    writeDir(dir, r.mean);
    writeDir(dir, r.variance, "_variance");
    vct::writeExr(dir / "surface_id.exr", r.surfaceId.width, r.surfaceId.height, r.surfaceId.pixels);
    vct::test::writeTextFile(
        dir / "reference.json",
        "{" + extra +
            R"("scene": "synthetic", "spp": 16, "bounces": 1, "surfaces": [)"
            R"({"id": 0, "name": "room/red", "material": 0}, {"id": 1, "name": "room/green"},)"
            R"({"id": 5, "name": "unused"}]})");
}

// A reference directory and a vct directory (× 2 / × 1) under a fresh test directory.
struct Dirs {
    fs::path root, reference, image;
};
Dirs writeDirs(const std::string& name, const TruthReference& reference, const LightBuffers& vctLight) {
    Dirs d{vct::test::freshOutputDir("truth/" + name), {}, {}};
    d.reference = d.root / "reference";
    d.image = d.root / "vct";
    fs::create_directories(d.reference);
    fs::create_directories(d.image);
    writeReferenceDir(d.reference, reference);
    writeDir(d.image, vctLight);
    return d;
}

json readJson(const fs::path& path) {
    std::ifstream file(path);
    EXPECT_TRUE(file.good()) << path;
    return file ? json::parse(file) : json::object();
}

// Exit status 1 or 2 with exactly one line on stderr, "vct: error: ...", naming `needle`.
void expectOneLineError(const vct::test::RunResult& r, int code, const std::string& needle) {
    ASSERT_TRUE(r.exited()) << r.describe();
    EXPECT_EQ(r.exitCode, code) << r.describe();
    EXPECT_EQ(r.err.rfind("vct: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.err;
}

// ---- the metrics, called directly ----

TEST(TruthMetrics, RatiosPerSurfaceAreExact) {
    const TruthReference reference = makeReference();
    const vct::TruthComparison c = vct::compareWithTruth(reference, makeScaledVct(), 1.0f);
    EXPECT_EQ(c.backgroundPixels, 4u);
    EXPECT_EQ(c.image.pixels, 28u);
    ASSERT_EQ(c.surfaces.size(), 2u);  // id 5 has no pixel: left out
    EXPECT_EQ(c.surfaces[0].id, 0);
    EXPECT_EQ(c.surfaces[0].name, "room/red");
    EXPECT_EQ(c.surfaces[0].sums.pixels, 16u);
    EXPECT_EQ(c.surfaces[1].name, "room/green");
    EXPECT_EQ(c.surfaces[1].sums.pixels, 12u);
    for (const auto& [surface, expected] : {std::pair{0, 2.0}, std::pair{1, 1.0}}) {
        const vct::RegionRatios& s = c.surfaces[size_t(surface)].sums;
        for (const vct::LuminanceSums* sums : {&s.indirect, &s.diffuse, &s.specular, &s.direct}) {
            ASSERT_TRUE(sums->ratio().has_value());
            EXPECT_NEAR(*sums->ratio(), expected, 1e-5) << "surface " << surface;
        }
    }
    // Whole image: (2 S0 + S1) / (S0 + S1) per quantity, S from the definitions above.
    const std::pair<const vct::LuminanceSums*, Rgb (*)(uint32_t, uint32_t)> quantities[] = {
        {&c.image.indirect, refIndirect},
        {&c.image.diffuse, refDiffuse},
        {&c.image.specular, refSpecular},
        {&c.image.direct, refDirect}};
    for (const auto& [sums, f] : quantities) {
        const double expected = sumLum(f, -2, true) / sumLum(f, -2, false);
        ASSERT_TRUE(sums->ratio().has_value());
        EXPECT_NEAR(*sums->ratio(), expected, 1e-5);
        EXPECT_NEAR(sums->reference, sumLum(f, -2, false), 1e-5);
        // The background (× 7) is left out: with it the ratio would be well above.
        EXPECT_GT(expected, 1.2);
        EXPECT_LT(expected, 1.9);
    }
}

TEST(TruthMetrics, ReferenceNoiseOnEachSum) {
    const vct::TruthComparison c = vct::compareWithTruth(makeReference(), makeScaledVct(), 1.0f);
    const double w2 = 0.2126 * 0.2126 + 0.7152 * 0.7152 + 0.0722 * 0.0722;  // Σ_c w_c²
    // Surface 0 has 16 pixels; the indirect's variance is var_final + var_direct (the upper bound).
    const vct::RegionRatios& s0 = c.surfaces[0].sums;
    const std::pair<const vct::LuminanceSums*, std::pair<Rgb (*)(uint32_t, uint32_t), double>> cases[] = {
        {&s0.indirect, {refIndirect, double(kVarFinal) + double(kVarDirect)}},
        {&s0.diffuse, {refDiffuse, double(kVarDiffuse)}},
        {&s0.specular, {refSpecular, double(kVarSpecular)}},
        {&s0.direct, {refDirect, double(kVarDirect)}}};
    for (const auto& [sums, what] : cases) {
        const double expected = std::sqrt(16.0 * w2 * what.second) / sumLum(what.first, 0, false);
        ASSERT_TRUE(sums->referenceNoise().has_value());
        EXPECT_NEAR(*sums->referenceNoise(), expected, 1e-6 * expected);
    }
}

TEST(TruthMetrics, RelMseSubtractsTheReferenceNoise) {
    // vct equal to the reference: (v − r)² = 0, so relMSE = −mean(var / (r² + 1e-3)) = −relNoise exactly, and
    // the raw relMSE (relMse + relNoise) is 0. The value is kept negative (an unbiased estimate), not
    // clamped.
    const TruthReference reference = makeReference();
    const vct::TruthComparison same = vct::compareWithTruth(reference, reference.mean, 1.0f);
    double noise = 0.0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < 7; ++x)
            for (float v : refFinal(x, y)) noise += double(kVarFinal) / (double(v) * v + 1e-3);
    noise /= 28.0 * 3.0;
    EXPECT_EQ(same.finalError.samples, 84u);
    EXPECT_NEAR(same.finalError.relNoise, noise, 1e-9 * noise);
    EXPECT_NEAR(same.finalError.relMse, -noise, 1e-9 * noise);
    EXPECT_NEAR(same.finalError.relMse + same.finalError.relNoise, 0.0, 1e-15);
    for (const vct::TruthError* e : {&same.indirectError, &same.diffuseError, &same.specularError}) {
        EXPECT_GT(e->relNoise, 1e-5);  // variances ≥ 1e-4 over r² + ε ≤ ~3: ≥ 3e-5
        EXPECT_NEAR(e->relMse, -e->relNoise, 1e-12);
    }

    // A known error: diffuse + 0.125 everywhere gives mean(0.125² / (r² + ε)) − noise.
    LightBuffers shifted = reference.mean;
    shifted.diffuse = makeImage([](uint32_t x, uint32_t y) {
        Rgb c = refDiffuse(x, y);
        for (float& v : c) v += 0.125f;
        return c;
    });
    const vct::TruthComparison off = vct::compareWithTruth(reference, shifted, 1.0f);
    double expected = 0.0, expectedNoise = 0.0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < 7; ++x)
            for (float v : refDiffuse(x, y)) {
                const double d = double(v + 0.125f) - double(v);
                expected += (d * d - double(kVarDiffuse)) / (double(v) * v + 1e-3);
                expectedNoise += double(kVarDiffuse) / (double(v) * v + 1e-3);
            }
    EXPECT_NEAR(off.diffuseError.relMse, expected / 84.0, 1e-9);
    EXPECT_NEAR(off.diffuseError.relNoise, expectedNoise / 84.0, 1e-12);
    EXPECT_NEAR(off.finalError.relMse, -same.finalError.relNoise, 1e-12);  // final untouched
}

// A flat 128×128 frame (one surface) whose light is `truth`, plus noise: each pixel and channel gets
// amplitude × (a uniform number in [−1, 1]) from a generator seeded by `seed` (an LCG: the same on every host).
LightBuffers noisyLight(float truth, float amplitude, uint32_t seed) {
    uint32_t state = seed * 747796405u + 2891336453u;
    auto next = [&state]() {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) * (2.0f / 16777216.0f) - 1.0f;
    };
    auto image = [&](float base) {
        return makeImage(
            [&](uint32_t, uint32_t) {
                return Rgb{base + amplitude * next(), base + amplitude * next(), base + amplitude * next()};
            },
            128, 128);
    };
    // final = direct + indirect: direct noiseless, so the indirect carries the final's noise.
    return {image(truth + 0.5f),
            makeImage(
                [](uint32_t, uint32_t) {
                    return Rgb{0.5f, 0.5f, 0.5f};
                },
                128, 128),
            image(truth), image(truth)};
}

TruthReference flatReference(const LightBuffers& mean) {
    TruthReference r;
    r.mean = mean;
    const ImageRgba32f zero = makeImage([](uint32_t, uint32_t) { return Rgb{0.0f, 0.0f, 0.0f}; }, 128, 128);
    r.variance = {zero, zero, zero, zero};
    r.surfaceId = zero;  // surface 0 everywhere
    return r;
}

TEST(TruthMetrics, ASecondReferenceMeasuresTheReferenceNoiseInThePsnr) {
    // The truth: 0.2 everywhere. Two references with independent noise of the same amplitude (same spp), and a
    // vct image 10 % too bright. Against the noise-free truth vct's PSNR is known; against a noisy reference
    // it is lower by the reference's noise, which the second reference measures.
    const float truth = 0.2f, amplitude = 0.03f;
    const LightBuffers exact = noisyLight(truth, 0.0f, 1), first = noisyLight(truth, amplitude, 1),
                       second = noisyLight(truth, amplitude, 2), vctLight = noisyLight(truth * 1.1f, 0.0f, 3);
    const TruthReference reference = flatReference(first);
    const vct::TruthComparison plain = vct::compareWithTruth(reference, vctLight, 1.0f);
    EXPECT_FALSE(plain.indirectError.srgbReferenceNoise.has_value());
    EXPECT_FALSE(plain.indirectError.srgbPsnrWithoutReferenceNoise().has_value());
    const double noisyPsnr = *plain.indirectError.srgbPsnr();
    const vct::TruthComparison c = vct::compareWithTruth(reference, vctLight, 1.0f, &second);
    EXPECT_EQ(c.indirectError.srgbMse, plain.indirectError.srgbMse);  // the MSE itself unchanged

    // The noise measured is the reference's own error against the truth, to the sampling error of 49152
    // values (measured 1.4 % off, 3.3 % with the finer second reference below; asserted within 5 %).
    const double own = vct::compareWithTruth(flatReference(exact), first, 1.0f).indirectError.srgbMse;
    ASSERT_TRUE(c.indirectError.srgbReferenceNoise.has_value());
    EXPECT_NEAR(*c.indirectError.srgbReferenceNoise / own, 1.0, 0.05);
    EXPECT_NEAR(*c.indirectError.referencePsnr(), 10.0 * std::log10(1.0 / own), 0.25);
    // vct's PSNR without the reference's noise is close to its PSNR against the truth, while the noisy
    // reference takes 2.85 dB off (measured; asserted ≥ 2.5). Close, not equal: it is the PSNR against the
    // reference's expected tone-mapped value E[T(r)], which the tone map's curvature moves from T(truth)
    // (Jensen): at this noise (±9 % per pixel, 1σ) 0.40 dB under (asserted within 0.45 dB); at ±29 % it was
    // 3.6 dB under, so the estimate holds only for references whose per-pixel noise is small.
    const double truePsnr =
        *vct::compareWithTruth(flatReference(exact), vctLight, 1.0f).indirectError.srgbPsnr();
    ASSERT_TRUE(c.indirectError.srgbPsnrWithoutReferenceNoise().has_value());
    EXPECT_NEAR(*c.indirectError.srgbPsnrWithoutReferenceNoise(), truePsnr, 0.45);
    EXPECT_GE(truePsnr - noisyPsnr, 2.5);
    const json j = vct::truthJson(c);
    EXPECT_NEAR(j["errors"]["indirect"]["psnr_srgb_without_reference_noise"].get<double>(), truePsnr, 0.45);
    EXPECT_TRUE(j["errors"]["indirect"]["psnr_srgb_reference"].is_number());
    EXPECT_NE(vct::formatTruthTable(c).find("PSNR without ref. noise"), std::string::npos);

    // A second reference with 4× the samples (half the noise amplitude: a quarter of the variance) measures the
    // same: the estimate does not depend on how the two references' noise compares.
    const LightBuffers finerSecond = noisyLight(truth, 0.5f * amplitude, 4);
    const vct::TruthComparison finer = vct::compareWithTruth(reference, vctLight, 1.0f, &finerSecond);
    EXPECT_NEAR(*finer.indirectError.srgbReferenceNoise / own, 1.0, 0.05);
    EXPECT_NEAR(*finer.indirectError.srgbPsnrWithoutReferenceNoise(), truePsnr, 0.45);

    // vct equal to the reference: within its noise, so no PSNR without it (null in JSON), never NaN.
    const vct::TruthComparison same = vct::compareWithTruth(reference, first, 1.0f, &second);
    EXPECT_FALSE(same.indirectError.srgbPsnrWithoutReferenceNoise().has_value());
    EXPECT_TRUE(vct::truthJson(same)["errors"]["indirect"]["psnr_srgb_without_reference_noise"].is_null());
    EXPECT_NE(vct::formatTruthTable(same).find("within the noise"), std::string::npos);

    // A second reference of another size: one message naming it.
    const LightBuffers small = makeScaledVct();
    EXPECT_THROW(vct::compareWithTruth(reference, vctLight, 1.0f, &small), vct::Error);
    try {
        vct::compareWithTruth(reference, vctLight, 1.0f, &small);
    } catch (const vct::Error& e) {
        EXPECT_NE(std::string(e.what()).find("second reference final is 8x4"), std::string::npos) << e.what();
    }
}

TEST(TruthMetrics, IdenticalImagesHaveNoFinitePsnrAndJsonSaysNull) {
    const TruthReference reference = makeReference();
    const vct::TruthComparison same = vct::compareWithTruth(reference, reference.mean, 1.0f);
    for (const vct::TruthError* e :
         {&same.finalError, &same.indirectError, &same.diffuseError, &same.specularError}) {
        EXPECT_EQ(e->srgbMse, 0.0);
        EXPECT_FALSE(e->srgbPsnr().has_value());
    }
    const json j = vct::truthJson(same);
    for (const char* light : {"final", "indirect", "diffuse", "specular"}) {
        EXPECT_TRUE(j["errors"][light]["psnr_srgb"].is_null()) << light;
        EXPECT_EQ(j["errors"][light]["mse_srgb"].get<double>(), 0.0) << light;
    }
    EXPECT_NE(vct::formatTruthTable(same).find(" inf "), std::string::npos);
}

TEST(TruthMetrics, PsnrIsCompareToneMappedsOnAFrameWithoutBackground) {
    // Without background every pixel counts, so the final's PSNR is exactly compareToneMapped's.
    const TruthReference reference = makeReference([](uint32_t x, uint32_t) { return x < 4 ? 0 : 1; });
    const LightBuffers vctLight = makeScaledVct();
    for (float exposure : {1.0f, 0.25f}) {
        const vct::TruthComparison c = vct::compareWithTruth(reference, vctLight, exposure);
        const double expected =
            vct::compareToneMapped(reference.mean.finalImage, vctLight.finalImage, exposure).psnr;
        ASSERT_TRUE(c.finalError.srgbPsnr().has_value());
        EXPECT_NEAR(*c.finalError.srgbPsnr(), expected, 1e-9);
        const double diffuse =
            vct::compareToneMapped(reference.mean.diffuse, vctLight.diffuse, exposure).psnr;
        EXPECT_NEAR(*c.diffuseError.srgbPsnr(), diffuse, 1e-9);
        // vct is the reference × 2, × 1 and (column 7, a surface here) × 7: a finite PSNR, 5 to 60 dB.
        EXPECT_GT(expected, 5.0);
        EXPECT_LT(expected, 60.0);
    }
}

TEST(TruthMetrics, BackgroundOnlyGivesNullsNotNaN) {
    const TruthReference reference = makeReference([](uint32_t, uint32_t) { return -1; });
    const vct::TruthComparison c = vct::compareWithTruth(reference, makeScaledVct(), 1.0f);
    EXPECT_TRUE(c.surfaces.empty());
    EXPECT_EQ(c.image.pixels, 0u);
    EXPECT_EQ(c.backgroundPixels, 32u);
    EXPECT_FALSE(c.image.indirect.ratio().has_value());
    EXPECT_FALSE(c.image.indirect.referenceNoise().has_value());
    EXPECT_FALSE(c.finalError.srgbPsnr().has_value());
    const json j = vct::truthJson(c);
    for (const char* light : {"indirect", "diffuse", "specular", "direct"}) {
        EXPECT_TRUE(j["image"][light]["ratio"].is_null()) << light;
        EXPECT_TRUE(j["image"][light]["reference_noise"].is_null()) << light;
    }
    for (const char* light : {"final", "indirect", "diffuse", "specular"})
        for (const char* metric : {"psnr_srgb", "mse_srgb", "rel_mse", "rel_mse_noise", "rel_mse_raw"})
            EXPECT_TRUE(j["errors"][light][metric].is_null()) << light << " " << metric;
    const std::string text = j.dump() + vct::formatTruthTable(c);
    EXPECT_EQ(text.find("nan"), std::string::npos) << text;
    EXPECT_EQ(text.find("NaN"), std::string::npos) << text;
}

TEST(TruthMetrics, ZeroReferenceSumOnASurfaceIsNull) {
    // Surface 1's reference specular is 0 (vct's is not): that ratio is null, the others are not.
    TruthReference reference = makeReference();
    reference.mean.specular = makeImage([](uint32_t x, uint32_t y) {
        return surfaceAt(x, y) == 1 ? Rgb{0, 0, 0} : refSpecular(x, y);
    });
    const vct::TruthComparison c = vct::compareWithTruth(reference, makeScaledVct(), 1.0f);
    EXPECT_FALSE(c.surfaces[1].sums.specular.ratio().has_value());
    EXPECT_FALSE(c.surfaces[1].sums.specular.referenceNoise().has_value());
    ASSERT_TRUE(c.surfaces[1].sums.diffuse.ratio().has_value());
    EXPECT_NEAR(*c.surfaces[1].sums.diffuse.ratio(), 1.0, 1e-5);
    EXPECT_TRUE(vct::truthJson(c)["surfaces"][1]["specular"]["ratio"].is_null());
}

TEST(TruthMetrics, InputProblemsNameThePixel) {
    ImageRgba32f image = makeImage(refFinal);
    EXPECT_FALSE(vct::nonFiniteProblem(image).has_value());
    image.pixels[(1 * kWidth + 3) * 4 + 1] = std::nanf("");
    EXPECT_EQ(vct::nonFiniteProblem(image).value_or(""), "pixel (3, 1) G is NaN");
    image.pixels[(1 * kWidth + 3) * 4 + 1] = INFINITY;
    EXPECT_EQ(vct::nonFiniteProblem(image).value_or(""), "pixel (3, 1) G is infinite");
    image.pixels[(1 * kWidth + 3) * 4 + 1] = 0.5f;
    image.pixels[3] = std::nanf("");  // alpha is not looked at
    EXPECT_FALSE(vct::nonFiniteProblem(image).has_value());

    ImageRgba32f variance = makeImage([](uint32_t, uint32_t) { return Rgb{0, 0, 0}; });
    EXPECT_FALSE(vct::varianceProblem(variance).has_value());
    variance.pixels[(2 * kWidth) * 4 + 2] = -1e-6f;
    EXPECT_EQ(vct::varianceProblem(variance).value_or(""), "pixel (0, 2) B is negative (-1e-06)");

    ImageRgba32f ids = makeReference().surfaceId;
    EXPECT_FALSE(vct::surfaceIdProblem(ids).has_value());
    ids.pixels[4] = 0.5f;
    EXPECT_NE(vct::surfaceIdProblem(ids).value_or("").find("pixel (1, 0) has surface id 0.5"),
              std::string::npos);
    ids.pixels[4] = -2.0f;
    EXPECT_NE(vct::surfaceIdProblem(ids).value_or("").find("surface id -2"), std::string::npos);
    ids.pixels[4] = std::nanf("");
    EXPECT_TRUE(vct::surfaceIdProblem(ids).has_value());
}

TEST(TruthMetrics, SizeMismatchOrBadIdsThrowNamingTheBuffer) {
    const TruthReference reference = makeReference();
    LightBuffers vctLight = makeScaledVct();
    vctLight.diffuse = makeImage(refDiffuse, 4, 4);
    try {
        vct::compareWithTruth(reference, vctLight, 1.0f);
        ADD_FAILURE() << "no error for a 4x4 diffuse";
    } catch (const vct::Error& e) {
        EXPECT_EQ(std::string(e.what()), "vct diffuse_indirect is 4x4, the reference's final 8x4");
    }
    EXPECT_THROW(vct::log2RatioMap(reference, vctLight, vct::Light::Diffuse), vct::Error);
    TruthReference badIds = makeReference();
    badIds.surfaceId.pixels[0] = std::nanf("");
    EXPECT_THROW(vct::compareWithTruth(badIds, makeScaledVct(), 1.0f), vct::Error);
}

TEST(TruthMetrics, Log2RatioMaps) {
    const TruthReference reference = makeReference();
    const LightBuffers vctLight = makeScaledVct();
    const std::vector<float> values = vct::log2RatioMap(reference, vctLight, vct::Light::Indirect);
    ASSERT_EQ(values.size(), size_t(kWidth) * kHeight);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const double r = lum(refIndirect(x, y));
            const double expected = surfaceAt(x, y) == -1  ? 0.0
                                    : surfaceAt(x, y) == 0 ? std::log2((2.0 * r + 1e-4) / (r + 1e-4))
                                                           : 0.0;
            EXPECT_NEAR(values[y * kWidth + x], expected, 1e-5) << x << ", " << y;
        }
    // Surface 0 at log2 ≈ 1 (half way to red): (255, 128, 128); surface 1 white; background black.
    const vct::ImageRgba8 png =
        vct::log2RatioPng(values, vct::surfaceIds(reference.surfaceId), kWidth, kHeight);
    auto at = [&](uint32_t x, uint32_t y) {
        const uint8_t* p = png.pixels.data() + (size_t(y) * kWidth + x) * 4;
        return std::array<int, 4>{p[0], p[1], p[2], p[3]};
    };
    const std::array<int, 4> half = at(0, 0);
    EXPECT_EQ(half[0], 255);
    EXPECT_NEAR(half[1], 128, 1);  // log2((2r + ε)/(r + ε)) is 1 less 1e-4 / r or so
    EXPECT_NEAR(half[2], 128, 1);
    EXPECT_EQ(at(5, 2), (std::array<int, 4>{255, 255, 255, 255}));
    EXPECT_EQ(at(7, 3), (std::array<int, 4>{0, 0, 0, 255}));
    // Clamped at ±2: blue at −2 and below.
    std::vector<float> extreme(values.size(), -5.0f);
    extreme[1] = 3.0f;
    const vct::ImageRgba8 clamped =
        vct::log2RatioPng(extreme, std::vector<int>(extreme.size(), 0), kWidth, kHeight);
    EXPECT_EQ(clamped.pixels[0], 0);
    EXPECT_EQ(clamped.pixels[1], 0);
    EXPECT_EQ(clamped.pixels[2], 255);
    EXPECT_EQ(clamped.pixels[4], 255);
    EXPECT_EQ(clamped.pixels[5], 0);
    EXPECT_EQ(clamped.pixels[6], 0);
}

// ---- the command ----

TEST(TruthCompareCli, RatiosJsonAndMaps) {
    const Dirs d = writeDirs("ratios", makeReference(), makeScaledVct());
    const fs::path maps = d.root / "maps";
    const auto r = vct::test::runVct({"compare", "--reference-dir", d.reference.string(), "--image-dir",
                                      d.image.string(), "--maps", maps.string()},
                                     std::chrono::seconds(60));
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    EXPECT_NE(r.out.find("room/red"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("whole image"), std::string::npos) << r.out;
    const json j = readJson(d.image / "truth.json");  // the default --json
    ASSERT_EQ(j["surfaces"].size(), 2u);
    EXPECT_EQ(j["surfaces"][0]["name"], "room/red");
    EXPECT_EQ(j["surfaces"][0]["pixels"], 16);
    EXPECT_EQ(j["surfaces"][1]["id"], 1);
    for (const char* light : {"indirect", "diffuse", "specular", "direct"}) {
        EXPECT_NEAR(j["surfaces"][0][light]["ratio"].get<double>(), 2.0, 1e-5) << light;
        EXPECT_NEAR(j["surfaces"][1][light]["ratio"].get<double>(), 1.0, 1e-5) << light;
    }
    EXPECT_NEAR(j["image"]["indirect"]["ratio"].get<double>(),
                sumLum(refIndirect, -2, true) / sumLum(refIndirect, -2, false), 1e-5);
    EXPECT_EQ(j["pixels"], 28);
    EXPECT_EQ(j["background_pixels"], 4);
    EXPECT_EQ(j["exposure"], 1.0);
    EXPECT_EQ(j["reference"]["spp"], 16);
    EXPECT_EQ(j["reference"]["scene"], "synthetic");
    EXPECT_TRUE(j["errors"]["final"]["psnr_srgb"].is_number());
    for (const char* name : {"indirect", "diffuse", "specular"}) {
        const std::string base = std::string("log2_") + name;
        const vct::ImageRgba8 png = vct::readPng(maps / (base + ".png"));
        EXPECT_EQ(png.width, kWidth);
        const ImageRgba32f exr = vct::readExr(maps / (base + ".exr"));
        ASSERT_EQ(exr.height, kHeight);
        EXPECT_NEAR(exr.pixels[0], 1.0, 0.01) << name;      // surface 0: log2(2) ≈ 1
        EXPECT_NEAR(exr.pixels[5 * 4], 0.0, 1e-6) << name;  // surface 1: 0
        EXPECT_EQ(exr.pixels[7 * 4], 0.0f) << name;         // background: 0 (vct has × 7 there)
    }
    // --json elsewhere, --exposure recorded.
    const fs::path other = d.root / "other.json";
    const auto r2 = vct::test::runVct({"compare", "--reference-dir", d.reference.string(), "--image-dir",
                                       d.image.string(), "--json", other.string(), "--exposure", "0.5"},
                                      std::chrono::seconds(60));
    ASSERT_TRUE(r2.exited() && r2.exitCode == 0) << r2.describe();
    EXPECT_EQ(readJson(other)["exposure"], 0.5);
}

TEST(TruthCompareCli, SecondReferenceDirMeasuresTheReferenceNoise) {
    const TruthReference reference = makeReference();
    const Dirs d = writeDirs("second", reference, makeScaledVct());
    writeReferenceDir(d.reference, reference, R"("seed": 1, )");
    // The second reference: the first with its indirect light 1 % brighter on every surface pixel.
    TruthReference other = reference;
    other.mean.finalImage = makeImage([](uint32_t x, uint32_t y) {
        const Rgb f = refFinal(x, y), i = refIndirect(x, y);
        return Rgb{f[0] + 0.01f * i[0], f[1] + 0.01f * i[1], f[2] + 0.01f * i[2]};
    });
    auto run = [&](const fs::path& second) {
        return vct::test::runVct({"compare", "--reference-dir", d.reference.string(), "--image-dir",
                                  d.image.string(), "--second-reference-dir", second.string()},
                                 std::chrono::seconds(60));
    };
    const fs::path good = d.root / "seed2";
    fs::create_directories(good);
    writeReferenceDir(good, other, R"("seed": 2, )");
    const auto r = run(good);
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    EXPECT_NE(r.out.find("PSNR without ref. noise"), std::string::npos) << r.out;
    const json j = readJson(d.image / "truth.json");
    EXPECT_EQ(j["second_reference_dir"], good.string());
    const vct::TruthComparison direct = vct::compareWithTruth(reference, makeScaledVct(), 1.0f, &other.mean);
    EXPECT_NEAR(j["errors"]["final"]["mse_srgb_reference_noise"].get<double>(),
                *direct.finalError.srgbReferenceNoise, 1e-9);
    EXPECT_TRUE(j["errors"]["final"]["psnr_srgb_without_reference_noise"].is_number());
    EXPECT_EQ(j["errors"]["diffuse"]["mse_srgb_reference_noise"].get<double>(), 0.0);  // diffuse unchanged

    // Not an independent estimate of the same image: one line naming the second reference.json.
    const fs::path sameSeed = d.root / "seed1";
    fs::create_directories(sameSeed);
    writeReferenceDir(sameSeed, other, R"("seed": 1, )");
    expectOneLineError(run(sameSeed), 1, (sameSeed / "reference.json").string() + ": the same \"seed\"");
    const fs::path otherFrame = d.root / "frame";
    fs::create_directories(otherFrame);
    writeReferenceDir(otherFrame, other, R"("seed": 2, "frame": 7, )");
    expectOneLineError(run(otherFrame), 1, "\"frame\" is 7");
    expectOneLineError(run(d.root / "absent"), 1, (d.root / "absent").string() + ": no such directory");
}

TEST(TruthCompareCli, IdenticalImagesPsnrIsNullAndRelMseIsMinusNoise) {
    // The reference directory holds final/direct/diffuse/specular itself: compare it with itself.
    const TruthReference reference = makeReference();
    const Dirs d = writeDirs("identical", reference, reference.mean);
    const fs::path out = d.root / "truth.json";
    const auto r = vct::test::runVct({"compare", "--reference-dir", d.reference.string(), "--image-dir",
                                      d.image.string(), "--json", out.string()},
                                     std::chrono::seconds(60));
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    EXPECT_NE(r.out.find(" inf "), std::string::npos) << r.out;
    const json j = readJson(out);
    for (const char* light : {"final", "indirect", "diffuse", "specular"}) {
        const json& e = j["errors"][light];
        EXPECT_TRUE(e["psnr_srgb"].is_null()) << light;
        const double noise = e["rel_mse_noise"].get<double>();
        EXPECT_GT(noise, 1e-5) << light;
        EXPECT_NEAR(e["rel_mse"].get<double>(), -noise, 1e-12) << light;
        EXPECT_NEAR(e["rel_mse_raw"].get<double>(), 0.0, 1e-12) << light;
    }
}

TEST(TruthCompareCli, BackgroundOnlyGivesNullRatios) {
    const Dirs d =
        writeDirs("background", makeReference([](uint32_t, uint32_t) { return -1; }), makeScaledVct());
    const auto r = vct::test::runVct(
        {"compare", "--reference-dir", d.reference.string(), "--image-dir", d.image.string()},
        std::chrono::seconds(60));
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    const json j = readJson(d.image / "truth.json");
    EXPECT_TRUE(j["surfaces"].empty());
    EXPECT_EQ(j["pixels"], 0);
    for (const char* light : {"indirect", "diffuse", "specular", "direct"})
        EXPECT_TRUE(j["image"][light]["ratio"].is_null()) << light;
    EXPECT_TRUE(j["errors"]["final"]["rel_mse"].is_null());
    std::ifstream file(d.image / "truth.json");
    const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("NaN"), std::string::npos);
    EXPECT_EQ(text.find("nan"), std::string::npos);
    EXPECT_EQ(text.find("Infinity"), std::string::npos);
}

TEST(TruthCompareCli, BadInputsEndWithOneLineNamingTheFile) {
    const TruthReference reference = makeReference();
    auto run = [](const Dirs& d) {
        return vct::test::runVct(
            {"compare", "--reference-dir", d.reference.string(), "--image-dir", d.image.string()},
            std::chrono::seconds(60));
    };
    {  // a vct buffer missing (rendered without --aux)
        const Dirs d = writeDirs("missing", reference, makeScaledVct());
        fs::remove(d.image / "specular_indirect.exr");
        expectOneLineError(run(d), 1, (d.image / "specular_indirect.exr").string() + ": no such file");
    }
    {  // reference.json missing
        const Dirs d = writeDirs("missing_json", reference, makeScaledVct());
        fs::remove(d.reference / "reference.json");
        expectOneLineError(run(d), 1, (d.reference / "reference.json").string() + ": no such file");
    }
    {  // a variance of another size
        const Dirs d = writeDirs("size", reference, makeScaledVct());
        const ImageRgba32f small = makeImage(refFinal, 4, 4);
        vct::writeExr(d.reference / "direct_variance.exr", 4, 4, small.pixels);
        expectOneLineError(run(d), 1,
                           (d.reference / "direct_variance.exr").string() + ": 4x4, but " +
                               (d.reference / "final.exr").string() + " is 8x4");
    }
    {  // vct's final of another size
        const Dirs d = writeDirs("size_vct", reference, makeScaledVct());
        const ImageRgba32f big = makeImage(refFinal, 16, 4);
        vct::writeExr(d.image / "final.exr", 16, 4, big.pixels);
        expectOneLineError(run(d), 1, (d.image / "final.exr").string() + ": 16x4, but");
    }
    {  // NaN in vct's diffuse
        LightBuffers vctLight = makeScaledVct();
        vctLight.diffuse.pixels[(2 * kWidth + 5) * 4] = std::nanf("");
        const Dirs d = writeDirs("nan", reference, vctLight);
        expectOneLineError(run(d), 1,
                           (d.image / "diffuse_indirect.exr").string() + ": pixel (5, 2) R is NaN");
    }
    {  // a negative variance, a fractional surface id, an EXR that is not one
        const Dirs d = writeDirs("negative", reference, makeScaledVct());
        TruthReference bad = reference;
        bad.variance.finalImage.pixels[1] = -0.5f;
        vct::writeExr(d.reference / "final_variance.exr", kWidth, kHeight, bad.variance.finalImage.pixels);
        expectOneLineError(run(d), 1,
                           (d.reference / "final_variance.exr").string() + ": pixel (0, 0) G is negative");
        bad.surfaceId.pixels[0] = 1.5f;
        vct::writeExr(d.reference / "final_variance.exr", kWidth, kHeight,
                      reference.variance.finalImage.pixels);
        vct::writeExr(d.reference / "surface_id.exr", kWidth, kHeight, bad.surfaceId.pixels);
        expectOneLineError(run(d), 1,
                           (d.reference / "surface_id.exr").string() + ": pixel (0, 0) has surface id 1.5");
        vct::test::writeTextFile(d.reference / "surface_id.exr", "not an exr");
        expectOneLineError(run(d), 1, (d.reference / "surface_id.exr").string());
        vct::test::writeTextFile(d.reference / "reference.json", "{\"surfaces\": [{\"name\": \"x\"}]}");
        expectOneLineError(run(d), 1, "surfaces[0] has no integer \"id\"");
    }
    {  // a directory that does not exist
        const Dirs d = writeDirs("nodir", reference, makeScaledVct());
        fs::remove_all(d.image);
        expectOneLineError(run(d), 1, d.image.string() + ": no such directory");
    }
}

TEST(TruthCompareCli, UsageErrorsExit2) {
    const Dirs d = writeDirs("usage", makeReference(), makeScaledVct());
    const std::string ref = d.reference.string(), img = d.image.string();
    expectOneLineError(vct::test::runVct({"compare", "--reference-dir", ref}), 2, "--image-dir");
    expectOneLineError(vct::test::runVct({"compare", "--image-dir", img, "--maps", "m"}), 2,
                       "--reference-dir");
    expectOneLineError(
        vct::test::runVct({"compare", "--reference-dir", ref, "--image-dir", img, "--reference", "a.exr"}), 2,
        "different modes");
    expectOneLineError(
        vct::test::runVct({"compare", "--reference", "a.exr", "--image", "b.exr", "--json", "x"}), 2,
        "different modes");
    expectOneLineError(
        vct::test::runVct({"compare", "--reference-dir", ref, "--image-dir", img, "--exposure", "-1"}), 2,
        "--exposure");
    expectOneLineError(vct::test::runVct({"compare"}), 2, "--reference FILE");
    vct::test::writeTextFile(d.root / "file", "x");
    expectOneLineError(vct::test::runVct({"compare", "--reference-dir", ref, "--image-dir", img, "--maps",
                                          (d.root / "file").string()}),
                       2, "--maps");
}

TEST(TruthCompareCli, FileModeIsUnchanged) {
    // --reference A.exr --image B.exr as before: errors on linear HDR, --tonemap, --error-map.
    const fs::path dir = vct::test::freshOutputDir("truth/file_mode");
    const ImageRgba32f a = makeImage(refFinal), b = makeImage([](uint32_t x, uint32_t y) {
                                                    return scaled(refFinal(x, y), vctFactor(x, y));
                                                });
    vct::writeExr(dir / "a.exr", kWidth, kHeight, a.pixels);
    vct::writeExr(dir / "b.exr", kWidth, kHeight, b.pixels);
    const auto same = vct::test::runVct(
        {"compare", "--reference", (dir / "a.exr").string(), "--image", (dir / "a.exr").string()});
    ASSERT_TRUE(same.exited() && same.exitCode == 0) << same.describe();
    EXPECT_NE(same.out.find("mse 0  rel_mse 0  psnr inf dB"), std::string::npos) << same.out;
    const auto r =
        vct::test::runVct({"compare", "--reference", (dir / "a.exr").string(), "--image",
                           (dir / "b.exr").string(), "--tonemap", "--error-map", (dir / "map.png").string()});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    const vct::ImageError expected = vct::compareImages(a, b);
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), vct::formatImageError(expected));
    EXPECT_NE(r.out.find("tone-mapped sRGB (peak 1): "), std::string::npos) << r.out;
    EXPECT_EQ(vct::readPng(dir / "map.png").width, kWidth);
}

}  // namespace
