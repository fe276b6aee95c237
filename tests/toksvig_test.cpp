// Normal-map filtering (shaders/lib/toksvig.glsl, docs/design.md §4): the CPU properties of Toksvig's roughness
// and of geometric specular AA, and the measurement that decides whether Toksvig helps: the `plane` scene
// rendered at 4× the resolution with the normal map read at level 0 (--texture-lod0: unfiltered, so each sample
// is a point sample of the true surface) and box-filtered down is the reference; the 1× render with Toksvig must
// be closer to it (MSE on linear HDR) than the 1× render without.
//
// Before --texture-lod0 the reference sampled the normal map's mips too (at 4× only 2 levels finer, and the
// bumps are averaged flat from level 2 on), so it was no ground truth; see CloserToTheSupersampledReference
// for the size the 4× reference needs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "render/shader_math.h"
#include "report/image_metrics.h"
#include "test_util.h"

namespace vct {
namespace {

namespace g = vct::glsl;
namespace fs = std::filesystem;

TEST(Toksvig, UnitLengthLeavesRoughnessUnchanged) {
    EXPECT_EQ(g::toksvigVariance(1.0f), 0.0f);
    EXPECT_EQ(g::toksvigVariance(1.2f), 0.0f);  // quantisation can overshoot 1
    for (float a2 : {0.0f, 1e-4f, 0.04f, 0.5f, 1.0f}) {
        EXPECT_FLOAT_EQ(g::toksvigAlpha2(a2, g::toksvigVariance(1.0f)), a2);
        EXPECT_FLOAT_EQ(g::toksvigAlpha2Exact(a2, g::toksvigVariance(1.0f)), a2);
    }
}

TEST(Toksvig, ShortNormalsStayFiniteAndClamped) {
    for (float r : {0.0f, 1e-9f, 1e-3f, 0.01f, -1.0f}) {
        const float s2 = g::toksvigVariance(r);
        EXPECT_TRUE(std::isfinite(s2)) << r;
        for (float a2 : {0.0f, 0.3f, 1.0f}) {
            for (float out : {g::toksvigAlpha2(a2, s2), g::toksvigAlpha2Exact(a2, s2)}) {
                EXPECT_TRUE(std::isfinite(out)) << r;
                EXPECT_LE(out, 1.0f);
                EXPECT_GE(out, a2 - 1e-6f);
            }
        }
    }
    EXPECT_FLOAT_EQ(g::toksvigAlpha2(0.0f, g::toksvigVariance(0.0f)), 1.0f);
}

TEST(Toksvig, MonotonicInLengthAndRoughness) {
    for (float a2 : {0.0f, 1e-3f, 0.1f, 0.6f}) {
        float prevSmall = 2.0f, prevExact = 2.0f;
        for (float r = 0.0f; r <= 1.0f; r += 1.0f / 256.0f) {  // longer average: less roughness
            const float s2 = g::toksvigVariance(r);
            const float small = g::toksvigAlpha2(a2, s2), exact = g::toksvigAlpha2Exact(a2, s2);
            EXPECT_LE(small, prevSmall) << r;
            EXPECT_LE(exact, prevExact) << r;
            prevSmall = small;
            prevExact = exact;
        }
    }
    for (float r : {0.3f, 0.9f, 0.999f})
        for (float a2 = 0.0f; a2 < 1.0f; a2 += 0.05f) {
            const float s2 = g::toksvigVariance(r);
            EXPECT_LE(g::toksvigAlpha2(a2, s2), g::toksvigAlpha2(a2 + 0.05f, s2) + 1e-6f);
            EXPECT_LE(g::toksvigAlpha2Exact(a2, s2), g::toksvigAlpha2Exact(a2 + 0.05f, s2) + 1e-6f);
        }
}

TEST(Toksvig, VariantsAgreeForSmallVariance) {
    for (float a2 : {0.0f, 1e-3f, 0.02f, 0.1f})
        for (float s2 : {1e-5f, 1e-4f, 1e-3f}) {
            const float small = g::toksvigAlpha2(a2, s2), exact = g::toksvigAlpha2Exact(a2, s2);
            // They differ at second order: (2σ²)² and α²·2σ² terms.
            EXPECT_NEAR(small, exact, 4.0f * s2 * (s2 + a2) + 1e-7f) << a2 << " " << s2;
        }
}

TEST(SpecularAA, ZeroDerivativesAddNothingAndTheAdditionIsBounded) {
    EXPECT_EQ(g::specularAAVariance(0.0f, 0.0f), 0.0f);
    for (float a2 : {0.0f, 0.01f, 0.5f, 1.0f})
        EXPECT_FLOAT_EQ(g::specularAAAlpha2(a2, g::specularAAVariance(0.0f, 0.0f), g::SPECULAR_AA_THRESHOLD),
                        a2);
    const float huge = g::specularAAVariance(1e30f, INFINITY);
    for (float a2 : {0.0f, 0.01f, 0.5f, 0.9f}) {
        float prev = a2;
        for (float d2 : {1e-4f, 1e-2f, 0.1f, 1.0f, 4.0f}) {
            const float out =
                g::specularAAAlpha2(a2, g::specularAAVariance(d2, d2), g::SPECULAR_AA_THRESHOLD);
            EXPECT_GE(out, prev);
            EXPECT_LE(out, std::min(a2 + g::SPECULAR_AA_THRESHOLD, 1.0f) + 1e-6f);
            prev = out;
        }
        const float out = g::specularAAAlpha2(a2, huge, g::SPECULAR_AA_THRESHOLD);
        EXPECT_TRUE(std::isfinite(out));
        EXPECT_FLOAT_EQ(out, std::min(a2 + g::SPECULAR_AA_THRESHOLD, 1.0f));
    }
    EXPECT_FLOAT_EQ(g::specularAAVariance(0.5f, 0.25f), g::SPECULAR_AA_KERNEL_VARIANCE * 0.75f);
}

// ---- GPU: the supersampling measurement ----

// Every render of the measurement: one frame of the `plane` scene, geometric specular AA off in all of them so
// that only Toksvig differs between the 1× renders (specular AA would widen the lobe from the normals'
// screen-space derivatives, a second filter that would blur which one helps), and GI off: the plane reflects
// nothing but the constant environment, which GI off gives too, and the large reference renders 8× faster.
ImageRgba32f renderPlane(const std::string& name, uint32_t width, uint32_t height,
                         const std::vector<std::string>& extra) {
    const fs::path dir = test::freshOutputDir("toksvig/" + name);
    std::vector<std::string> args = {
        "render",   "--scene", "plane", "--size",     std::to_string(width) + "x" + std::to_string(height),
        "--frames", "1",       "--out", dir.string(), "--specular-aa",
        "off",      "--gi",    "off"};
    args.insert(args.end(), extra.begin(), extra.end());
    test::RunResult run = test::runVct(args);
    EXPECT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    ImageRgba32f image = readExr(dir / "final.exr");
    EXPECT_EQ(image.width, width);
    EXPECT_EQ(image.height, height);
    EXPECT_EQ(test::countNonFinite(image.pixels), 0u) << name;
    return image;
}

// The ground truth: `factor`× the resolution, every material texture read at level 0 (--texture-lod0: no
// mips, so no Toksvig input either; Toksvig off), i.e. point samples of the unfiltered normal map.
ImageRgba32f renderReference(uint32_t width, uint32_t height) {
    return renderPlane("reference-" + std::to_string(width) + "x" + std::to_string(height), width, height,
                       {"--toksvig", "off", "--texture-lod0"});
}

// factor × factor box filter of the RGB channels (alpha 1).
ImageRgba32f boxDown(const ImageRgba32f& image, uint32_t factor) {
    ImageRgba32f out{image.width / factor, image.height / factor, {}};
    out.pixels.assign(size_t(out.width) * out.height * 4, 0.0f);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x)
            for (size_t c = 0; c < 3; ++c)
                out.pixels[(size_t(y / factor) * out.width + x / factor) * 4 + c] +=
                    image.pixels[(size_t(y) * image.width + x) * 4 + c] / float(factor * factor);
    for (size_t i = 3; i < out.pixels.size(); i += 4) out.pixels[i] = 1.0f;
    return out;
}

struct Errors {
    double on, off;
};

// The 1× renders at width × height with Toksvig on and off against `reference` (already box-filtered).
Errors compare(const ImageRgba32f& reference, uint32_t width, uint32_t height, uint32_t factor,
               const char* note = "") {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    const ImageRgba32f on = renderPlane("on-" + size, width, height, {"--toksvig", "on"});
    const ImageRgba32f off = renderPlane("off-" + size, width, height, {"--toksvig", "off"});
    const Errors errors{compareImages(reference, on).mse, compareImages(reference, off).mse};
    std::printf("plane %s vs %ux box-filtered level-0 reference: MSE toksvig on %.6g, off %.6g%s\n",
                size.c_str(), factor, errors.on, errors.off, note);
    return errors;
}

// Acceptance (issue 3 item 4): 640x360 against 2560x1440, and 160x90 against the same 2560x1440 (16×).
//
// The 1× size is 640x360, not smaller, because a 4× reference is only ground truth where 4× resolves the
// bumps: 8 texels of 2 mm, 15.6 mm, while a 640x360 pixel at the highlight (3.35 m away, 26.6° above the
// plane) spans ~17 mm along the view direction, so 4× gives ~3.6 samples per bump period. At 160x90 the 4×
// reference (640x360) gets ~1.1 samples per period along the view: below Nyquist, it aliases into moiré bands
// that show the flat-mirror highlight, and it is not converged: box-filtered to 160x90 its mean is 3.23 where
// 8× gives 1.89, 16× 1.09 and 32× 1.12 (MSE against the 32× one: 4× 774, 8× 55, 16× 8.0), so it sides with
// Toksvig off (on 771, off 85.3, printed below for the record, not asserted). At 640x360 the 4× reference is
// within MSE 29 of an 8× one (5120x2880): its remaining error is the glints of the 0.15-roughness lobe.
// Measured (lavapipe): 640x360 vs 4×: on 23.7, off 676; 160x90 vs 16×: on 6.17, off 782.
TEST(ToksvigGpu, CloserToTheSupersampledReference) {
    constexpr uint32_t kWidth = 640, kHeight = 360, kFactor = 4;
    const ImageRgba32f big = renderReference(kWidth * kFactor, kHeight * kFactor);
    if (big.width != kWidth * kFactor || big.height != kHeight * kFactor) return;  // reported above

    // Issue 9's margin: Toksvig at most 0.2× the error without it. Measured 23.7 / 676 = 0.035× at 640x360
    // and 6.17 / 782 = 0.0079× at 160x90.
    const Errors at4 = compare(boxDown(big, kFactor), kWidth, kHeight, kFactor);
    EXPECT_LE(at4.on, 0.2 * at4.off);
    const Errors at16 = compare(boxDown(big, 16), kWidth / 4, kHeight / 4, 16);
    EXPECT_LE(at16.on, 0.2 * at16.off);

    // For the record: 160x90 against its own 4× reference, which aliases (see above).
    const ImageRgba32f small = renderReference(kWidth, kHeight);
    if (small.width == kWidth && small.height == kHeight)
        compare(boxDown(small, kFactor), kWidth / 4, kHeight / 4, kFactor,
                " (reference aliased at this size: not asserted)");
}

// Roughness-0 materials (MetalRoughSpheresNoTextures' first column) with Toksvig and specular AA on: every
// buffer finite.
TEST(ToksvigGpu, RoughnessZeroStaysFinite) {
    const fs::path dir = test::freshOutputDir("toksvig/roughness0");
    const std::string scene =
        std::string(VCT_SHARED_SCENES) + "/MetalRoughSpheresNoTextures/glTF/MetalRoughSpheresNoTextures.gltf";
    if (!fs::exists(scene)) GTEST_SKIP() << scene << " not present";
    test::RunResult run =
        test::runVct({"render", "--scene", scene, "--size", "160x90", "--frames", "2", "--out", dir.string(),
                      "--aux", "--toksvig", "on", "--specular-aa", "on"});
    ASSERT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() == ".exr") {
            EXPECT_EQ(test::countNonFinite(readExr(entry.path()).pixels), 0u) << entry.path();
        }
    }
}

}  // namespace
}  // namespace vct
