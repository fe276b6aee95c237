// Normal-map filtering (shaders/lib/toksvig.glsl, DESIGN §3.2): the CPU properties of Toksvig's roughness and
// of geometric specular AA, and the measurement that decides whether Toksvig helps: the `plane` scene rendered
// at 4× the resolution without filtering and box-filtered down is the reference; the 1× render with Toksvig
// must be closer to it (MSE on linear HDR) than the 1× render without.
//
// The supersampling factor must be 16, not 4: the reference samples the normal map's mips too, and 4× only
// lowers the mip level by 2. The plane's bumps (8-texel period) are averaged away from level 2 on, so a 4×
// reference still shows the flat-mirror highlight and agrees with Toksvig off (measured at 160x90, exact
// variant: 4× reference MSE on 559, off 58.7; 8×: on 102, off 687; 16×: on 6.16, off 782; small-angle
// variant: 561 / 103 / 6.34). The 4× numbers are printed too, for the record.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "render/shader_math.h"
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
        EXPECT_FLOAT_EQ(g::specularAAAlpha2(a2, g::specularAAVariance(0.0f, 0.0f), g::SPECULAR_AA_THRESHOLD), a2);
    const float huge = g::specularAAVariance(1e30f, INFINITY);
    for (float a2 : {0.0f, 0.01f, 0.5f, 0.9f}) {
        float prev = a2;
        for (float d2 : {1e-4f, 1e-2f, 0.1f, 1.0f, 4.0f}) {
            const float out = g::specularAAAlpha2(a2, g::specularAAVariance(d2, d2), g::SPECULAR_AA_THRESHOLD);
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

constexpr uint32_t kWidth = 160, kHeight = 90, kFactor = 16;

ImageRgba32f renderPlane(const std::string& name, uint32_t factor, bool toksvig) {
    const fs::path dir = test::freshOutputDir("toksvig/" + name);
    const std::string size = std::to_string(kWidth * factor) + "x" + std::to_string(kHeight * factor);
    test::RunResult run = test::runVct({"render", "--scene", "plane", "--size", size, "--frames", "2", "--out",
                                        dir.string(), "--toksvig", toksvig ? "on" : "off", "--specular-aa", "off"});
    EXPECT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    return readExr(dir / "final.exr");
}

// factor × factor box filter of the RGB channels.
std::vector<float> boxDown(const ImageRgba32f& image, uint32_t factor) {
    const uint32_t w = image.width / factor, h = image.height / factor;
    std::vector<float> out(size_t(w) * h * 3, 0.0f);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x)
            for (size_t c = 0; c < 3; ++c)
                out[(size_t(y / factor) * w + x / factor) * 3 + c] +=
                    image.pixels[(size_t(y) * image.width + x) * 4 + c] / float(factor * factor);
    return out;
}

double mse(const std::vector<float>& reference, const ImageRgba32f& image) {
    double sum = 0.0;
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
        for (size_t c = 0; c < 3; ++c) {
            const double d = double(image.pixels[i * 4 + c]) - reference[i * 3 + c];
            sum += d * d;
        }
    return sum / double(image.width * image.height * 3);
}

TEST(ToksvigGpu, CloserToTheSupersampledReference) {
    const ImageRgba32f on = renderPlane("on", 1, true), off = renderPlane("off", 1, false);
    ASSERT_EQ(on.width, kWidth);
    ASSERT_EQ(off.width, kWidth);
    EXPECT_EQ(test::countNonFinite(on.pixels) + test::countNonFinite(off.pixels), 0u);
    for (uint32_t factor : {4u, kFactor}) {
        const ImageRgba32f big = renderPlane("reference" + std::to_string(factor), factor, false);
        ASSERT_EQ(big.width, kWidth * factor);
        EXPECT_EQ(test::countNonFinite(big.pixels), 0u);
        const std::vector<float> reference = boxDown(big, factor);
        const double errorOn = mse(reference, on), errorOff = mse(reference, off);
        std::printf("plane %ux%u vs %ux box-filtered reference: MSE toksvig on %.6g, off %.6g\n", kWidth, kHeight,
                    factor, errorOn, errorOff);
        if (factor == kFactor) {
            EXPECT_LT(errorOn, errorOff);
        }
    }
}

// Roughness-0 materials (MetalRoughSpheresNoTextures' first column) with Toksvig and specular AA on: every
// buffer finite.
TEST(ToksvigGpu, RoughnessZeroStaysFinite) {
    const fs::path dir = test::freshOutputDir("toksvig/roughness0");
    const std::string scene =
        std::string(VCT_SHARED_SCENES) + "/MetalRoughSpheresNoTextures/glTF/MetalRoughSpheresNoTextures.gltf";
    if (!fs::exists(scene)) GTEST_SKIP() << scene << " not present";
    test::RunResult run = test::runVct({"render", "--scene", scene, "--size", "160x90", "--frames", "2", "--out",
                                        dir.string(), "--aux", "--toksvig", "on", "--specular-aa", "on"});
    ASSERT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() == ".exr") {
            EXPECT_EQ(test::countNonFinite(readExr(entry.path()).pixels), 0u) << entry.path();
        }
    }
}

}  // namespace
}  // namespace vct
