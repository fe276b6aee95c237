// The spatio-temporal upsampling and adaptive re-tracing on the GPU (docs/design.md §6–8): cornell at trace
// scale 4 against the same frame traced at every pixel (trace scale 1), computed by the same program.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "report/image_metrics.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using vct::test::luminance;

// Renders cornell at 160x90 with a 32³ grid into a fresh directory with --aux; extra flags appended.
fs::path renderCornell(const std::string& name, std::vector<std::string> extra) {
    const fs::path dir = vct::test::freshOutputDir("upsample/" + name);
    // One bounce: these tests measure the upsampling against a light that stands still, which the default's
    // amortised gathers (docs/design.md §5.7) are not while they converge. The fixed cone set: with the
    // default turned cones trace scale 1 keeps a history and is no longer the every-pixel trace of the frame,
    // and the turn noise would count as the upsampling's error (design §5.5).
    std::vector<std::string> args = {"render",     "--scene",   "cornell", "--size",          "160x90",
                                     "--voxels",   "32",        "--aux",   "--validate",      "--out",
                                     dir.string(), "--bounces", "1",       "--cone-rotation", "off"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = vct::test::runVct(args);
    EXPECT_TRUE(r.exited() && r.exitCode == 0) << name << ": " << r.describe();
    return dir;
}

double mse(const fs::path& reference, const fs::path& image) {
    return vct::compareImages(vct::readExr(reference), vct::readExr(image)).mse;
}

// No NaN or Inf in any channel, and no hole: no pixel the upsampling leaves black, or far darker than the same
// frame traced at every pixel (`reference`, trace scale 1), where that trace has light. "Where it has light",
// not "everywhere": the top of cornell's tall box, a few voxels under the unlit ceiling, gets almost no
// indirect light at one bounce at 32³ (the path tracer: 0.006 at 320×180; the every-pixel trace 1e-4 on
// lavapipe and exactly 0 in a few pixels on an NVIDIA H200, where this test first failed), so a black pixel
// there is the trace's answer, not a hole. Used for diffuse and final.
// Measured (160×90, 32³, lavapipe): the lit mask holds 14 271–14 313 of 14 400 pixels; the darkest pixel
// against the trace (diffuse / final), without re-tracing: bilinear 0.119 / 0.234, normal 0.139 / 0.127, sg
// 0.138 / 0.134, sg after a cut 0.378 / 0.081 (pixels beside the tall box's edge, whose samples lie on the box);
// with it: sg 0.510 / 0.512, normal after a cut 0.378 / 0.271. Each case asserts about ⅔ of its minimum.
// Round 14 (the coarser mip's reach cleared at any blend weight, docs/design.md §5.3): the mask 14 203–14 263;
// bilinear 0.120 / 0.234, normal 0.025 / 0.138, sg 0.118 / 0.116, sg after a cut 0.384 / 0.077; with re-tracing sg
// 0.383 / 0.388, normal after a cut 0.384 / 0.307. Normal's 0.025 is one pixel of the contact shadow under the
// sphere (the every-pixel trace 0.0107, just over the mask's threshold, among pixels of 0.0002–0.01; the upsample
// without re-tracing 0.0003). The sg weights' darkest pixel is 0.118 / 0.116, and re-tracing lifts sg's to 0.383.
// Round 24 (a cone ends on a closed face read beyond it, docs/design.md §5.3): bilinear 0.076 / 0.234 (round 23
// 0.098), normal 0.022 / 0.173, sg 0.099 / 0.185, sg after a cut 0.209 / 0.065; with re-tracing sg 0.323 / 0.347,
// normal after a cut 0.209 / 0.329. Every bound is ⅔ of its case's smaller minimum.
constexpr float kLitLuminance = 0.005f;
void expectFiniteAndNoHoles(const fs::path& file, const fs::path& reference, const std::string& what,
                            double minRatio) {
    const vct::ImageRgba32f image = vct::readExr(file);
    const vct::ImageRgba32f traced = vct::readExr(reference);
    EXPECT_EQ(vct::test::countNonFinite(image.pixels), 0u) << what;
    ASSERT_EQ(image.pixels.size(), traced.pixels.size()) << what;
    size_t lit = 0, black = 0;
    double darkest = 1e30;
    for (size_t i = 0; i < image.pixels.size(); i += 4) {
        const float t = luminance(traced.pixels[i], traced.pixels[i + 1], traced.pixels[i + 2]);
        if (!(t >= kLitLuminance)) continue;
        ++lit;
        const float u = luminance(image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]);
        black += u > 0.0f ? 0 : 1;
        darkest = std::min(darkest, double(u) / double(t));
    }
    std::printf("%s: %zu lit pixels of %zu, darkest %.3fx the every-pixel trace\n", what.c_str(), lit,
                image.pixels.size() / 4, darkest);
    // The mask is most of the image (measured 99.1 %): the test cannot pass on an empty one.
    EXPECT_GE(double(lit), 0.95 * double(image.pixels.size() / 4)) << what;
    EXPECT_EQ(black, 0u) << what << ": black pixels where the every-pixel trace has light";
    EXPECT_GE(darkest, minRatio) << what;
}

TEST(UpsampleGpu, StaticCameraConvergesTowardTraceScale1) {
    // Without re-tracing, so that only the spatio-temporal accumulation closes the gap. Measured (160x90,
    // 32³, llvmpipe): final MSE 1.03e-3 after 1 frame, 1.86e-4 after 8, 1.88e-4 after 64.
    double first = 0.0, converged = 0.0;
    for (const char* frames : {"1", "48"}) {
        const fs::path ref =
            renderCornell(std::string("converge_ref_") + frames, {"--frames", frames, "--trace-scale", "1"});
        const fs::path low = renderCornell(std::string("converge_s4_") + frames,
                                           {"--frames", frames, "--trace-scale", "4", "--adaptive", "off"});
        (std::string(frames) == "1" ? first : converged) = mse(ref / "final.exr", low / "final.exr");
    }
    std::printf("trace scale 4 vs 1, final MSE: after 1 frame %.4g, after 48 frames %.4g\n", first,
                converged);
    EXPECT_LT(converged, 0.5 * first);
    EXPECT_LT(converged, 4e-4);
}

TEST(UpsampleGpu, FirstFrameAndCameraCutHaveNoNaNInfOrHoles) {
    // Every guide without re-tracing (the weights alone must never leave a hole) and sg with it; the first
    // frame and the frame right after a camera cut have no history. Each against the same frame traced at
    // every pixel.
    struct Case {
        std::string name;
        std::vector<std::string> flags;
        double minRatio;  // the darkest pixel against the every-pixel trace, ⅔ of the measured
    };
    const std::vector<Case> cases = {
        {"first_bilinear", {"--frames", "1", "--weights", "bilinear", "--adaptive", "off"}, 0.05},
        {"first_normal", {"--frames", "1", "--weights", "normal", "--adaptive", "off"}, 0.015},
        {"first_sg", {"--frames", "1", "--weights", "sg", "--adaptive", "off"}, 0.066},
        {"first_sg_adaptive", {"--frames", "1", "--weights", "sg"}, 0.215},
        {"cut_sg", {"--frames", "5", "--camera-cut", "4", "--weights", "sg", "--adaptive", "off"}, 0.043},
        {"cut_normal_adaptive", {"--frames", "5", "--camera-cut", "4", "--weights", "normal"}, 0.139}};
    const fs::path firstTraced = renderCornell("first_traced", {"--frames", "1", "--trace-scale", "1"});
    const fs::path cutTraced =
        renderCornell("cut_traced", {"--frames", "5", "--camera-cut", "4", "--trace-scale", "1"});
    for (const Case& c : cases) {
        std::vector<std::string> flags = c.flags;
        flags.insert(flags.end(), {"--trace-scale", "4"});
        const fs::path dir = renderCornell(c.name, flags);
        const fs::path traced = c.name.rfind("cut", 0) == 0 ? cutTraced : firstTraced;
        expectFiniteAndNoHoles(dir / "diffuse_indirect.exr", traced / "diffuse_indirect.exr",
                               c.name + " diffuse", c.minRatio);
        // Specular may be exactly black: at one bounce the glossy floor's sharp stripes mirror the ceiling,
        // which no light reaches (the path tracer agrees); finite it must be.
        EXPECT_EQ(vct::test::countNonFinite(vct::readExr(dir / "specular_indirect.exr").pixels), 0u)
            << c.name;
        expectFiniteAndNoHoles(dir / "final.exr", traced / "final.exr", c.name + " final", c.minRatio);
        EXPECT_EQ(vct::test::countNonFinite(vct::readExr(dir / "weight_sum.exr").pixels), 0u) << c.name;
    }
}

// The two layouts of the upsample pass (--upsample-layout, docs/design.md §6.8) run the same arithmetic per pixel:
// one invocation per low-res cell (the CPU default) and one per pixel with the samples in shared memory (the GPU
// default) give bit-identical images, aux images and re-trace masks included, with history and adaptive
// re-tracing, at both trace scales, for a guided and the unguided configuration, and at sizes that are and are not
// a multiple of the trace scale.
TEST(UpsampleGpu, CellAndPixelLayoutsGiveTheSameImages) {
    const std::vector<std::vector<std::string>> configurations = {
        {"--trace-scale", "4", "--weights", "sg", "--frames", "5"},
        {"--trace-scale", "2", "--weights", "bilinear", "--frames", "3"},
        {"--trace-scale", "4", "--weights", "normal", "--frames", "4", "--camera-cut", "3"},
        // Sizes that are a multiple of s: the per-cell layout reconstructs each quarter of a cell from the 3×3
        // samples its kernel reaches, as the per-pixel layout does (upsample.comp, WHOLE_CELLS).
        {"--trace-scale", "4", "--weights", "sg", "--frames", "5", "--size", "160x88"},
        {"--trace-scale", "2", "--weights", "normal", "--frames", "3", "--size", "160x88"},
        // Sizes that are not a multiple of s: the last low-res column and row are traced at clamped pixels (by 2
        // at frame 1's offset (2, 2)), where a pixel's kernel reaches past the 3×3 samples of the pixel layout.
        {"--trace-scale", "4", "--weights", "sg", "--frames", "3", "--size", "161x89"},
        {"--trace-scale", "2", "--weights", "sg", "--frames", "2", "--size", "161x89"}};
    int index = 0;
    for (const auto& flags : configurations) {
        const std::string name = "layouts_" + std::to_string(index++);
        std::vector<std::string> cell = flags, pixel = flags;
        cell.insert(cell.end(), {"--upsample-layout", "cell"});
        pixel.insert(pixel.end(), {"--upsample-layout", "pixel"});
        const fs::path a = renderCornell(name + "_cell", cell), b = renderCornell(name + "_pixel", pixel);
        for (const char* file :
             {"final.exr", "diffuse_indirect.exr", "specular_indirect.exr", "weight_sum.exr"}) {
            const vct::ImageRgba32f x = vct::readExr(a / file), y = vct::readExr(b / file);
            ASSERT_EQ(x.pixels.size(), y.pixels.size()) << name << " " << file;
            const vct::test::ExactDifference d = vct::test::exactDifference(x.pixels, y.pixels);
            EXPECT_EQ(d.different, 0u)
                << name << " " << file << ": largest relative difference " << d.largestRelative;
        }
    }
}

// The pixels that changed between two frames of the direct light: where the moving cube is or was.
std::vector<bool> changedPixels(const vct::ImageRgba32f& a, const vct::ImageRgba32f& b, int dilate) {
    const int w = int(a.width), h = int(a.height);
    std::vector<bool> changed(size_t(w) * h, false), grown(size_t(w) * h, false);
    for (size_t i = 0; i < changed.size(); ++i)
        for (int c = 0; c < 3; ++c)
            changed[i] = changed[i] || std::abs(a.pixels[i * 4 + c] - b.pixels[i * 4 + c]) > 0.01f;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!changed[size_t(y) * w + x]) continue;
            for (int dy = -dilate; dy <= dilate; ++dy)
                for (int dx = -dilate; dx <= dilate; ++dx) {
                    const int X = x + dx, Y = y + dy;
                    if (X >= 0 && Y >= 0 && X < w && Y < h) grown[size_t(Y) * w + X] = true;
                }
        }
    return grown;
}

TEST(UpsampleGpu, MovingObjectLeavesNoTrailAndIsReTracedAround) {
    // The cube circles the floor (4 s loop); over 8 frames it moves several pixels. "Near it": every pixel
    // whose direct light changed between frames 40 and 48, grown by 3 pixels (its old and new places and the
    // shadow it drags along). The fixed cone set (renderCornell): the turned cones' noise, which the two
    // histories average differently (docs/design.md §5.5), is not the upsampling's error.
    const fs::path ref40 = renderCornell("moving_ref40", {"--frames", "40", "--trace-scale", "1"});
    const fs::path ref48 = renderCornell("moving_ref48", {"--frames", "48", "--trace-scale", "1"});
    const fs::path low = renderCornell("moving_s4", {"--frames", "48", "--trace-scale", "4"});
    // The same without history: what the spatial upsampling alone gets wrong near the cube's edges.
    const fs::path spatial =
        renderCornell("moving_s4_spatial", {"--frames", "48", "--trace-scale", "4", "--temporal", "off"});
    const vct::ImageRgba32f reference = vct::readExr(ref48 / "final.exr");
    const std::vector<bool> near =
        changedPixels(vct::readExr(ref40 / "direct.exr"), vct::readExr(ref48 / "direct.exr"), 3);

    // Mean squared error over the pixels near (near = true) or away from the cube, and the share re-traced.
    struct RegionStats {
        double error = 0.0, retraced = 0.0;
    };
    auto stats = [&](const fs::path& dir, bool nearCube) {
        const vct::ImageRgba32f image = vct::readExr(dir / "final.exr");
        const vct::ImageRgba8 mask = vct::readPng(dir / "resample_mask.png");
        RegionStats s;
        size_t count = 0;
        for (size_t i = 0; i < near.size(); ++i) {
            if (near[i] != nearCube) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = double(image.pixels[i * 4 + c]) - reference.pixels[i * 4 + c];
                s.error += d * d / 3.0;
            }
            s.retraced += mask.pixels[i * 4] > 127 ? 1.0 : 0.0;
            ++count;
        }
        s.error /= double(std::max<size_t>(count, 1));
        s.retraced /= double(std::max<size_t>(count, 1));
        return s;
    };
    const size_t nearCount = size_t(std::count(near.begin(), near.end(), true));
    ASSERT_GT(nearCount, 50u) << "the cube did not move?";
    const RegionStats nearCube = stats(low, true), elsewhere = stats(low, false);
    const RegionStats nearSpatial = stats(spatial, true);
    std::printf(
        "near the moving cube (%zu px): MSE %.4g (spatial only %.4g), re-traced %.2f%%; elsewhere: MSE %.4g, "
        "re-traced %.2f%%\n",
        nearCount, nearCube.error, nearSpatial.error, 100.0 * nearCube.retraced, elsewhere.error,
        100.0 * elsewhere.retraced);
    // No trail: the history adds no ghost where the cube moves. Measured 2.3e-4 with history against 3.2e-4
    // spatial only (0.72x) with the isotropic tracer; with the tracer that converges to the path-traced truth
    // (issue 18) 4.97e-4 against 4.97e-4 (1.00x): the history no longer helps there, and must not hurt. Measured
    // again on the tree with the turned cones (here off, trace scales 1 and 4 bit-identical to before them):
    // 5.86e-4 against 7.58e-4 (0.77x).
    EXPECT_LE(nearCube.error, 1.03 * nearSpatial.error);
    // Away from the cube the history converges to the traced pixels: measured 6.9e-6, 0.03x the error near
    // it; again with the turned cones' tree: 2.53e-5, 0.043x.
    EXPECT_LE(elsewhere.error, 0.1 * nearCube.error);
    // The re-traced pixels gather around it: measured 1.8% of the pixels near it, 0.64% elsewhere (2.8x).
    EXPECT_GE(nearCube.retraced, 2.0 * elsewhere.retraced);
    EXPECT_GE(nearCube.retraced, 0.01);
}

TEST(UpsampleGpu, SgWeightsWithinMarginOfNormalAndReportsRetracing) {
    // The acceptance run at test size: one benchmark run, configurations interleaved, errors against the
    // trace-scale-1 reference of the same run after 64 frames.
    const fs::path dir = vct::test::freshOutputDir("upsample/benchmark");
    const auto r = vct::test::runVct({"benchmark", "--scene", "cornell", "--size", "160x90", "--voxels", "32",
                                      "--frames", "64", "--warmup", "10", "--trace-scale", "4", "--validate",
                                      "--out", dir.string()});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    std::printf("%s", r.out.c_str());
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "benchmark.json"));
    auto config = [&](const std::string& name) {
        for (const auto& c : report["configs"])
            if (c["name"] == name) return c;
        ADD_FAILURE() << "no configuration " << name;
        return nlohmann::json();
    };
    const auto normal = config("normal"), sg = config("sg"), sgAdaptive = config("sg+adaptive");
    // Measured (160x90, 32³, 64 frames): specular 2.21e-4 against 2.36e-4 (0.94x) with the isotropic tracer;
    // 4.32e-4 against 4.23e-4 (1.02x) with the tracer that converges to the path-traced truth (issue 18): on
    // its sharper specular signal the lobe weights no longer win at this size (left to issue 19); diffuse
    // equal to 0.3 %.
    // Converged on a static view both guides approach the traced pixels; the lobe matters most where the
    // history does not help (benchmarks/README.md: first frames, cuts, the moving camera).
    EXPECT_LE(sg["error"]["specular"]["mse"].get<double>(),
              1.05 * normal["error"]["specular"]["mse"].get<double>());
    EXPECT_LE(sg["error"]["diffuse"]["mse"].get<double>(),
              1.01 * normal["error"]["diffuse"]["mse"].get<double>());
    for (const auto& c : report["configs"]) {
        for (const char* buffer : {"diffuse", "specular", "final"})
            EXPECT_EQ(c["error"][buffer]["non_finite"], 0) << c["name"];
        const double fraction = c["resampled_fraction"].get<double>();
        EXPECT_GE(fraction, 0.0);
        EXPECT_LE(fraction, 1.0);
    }
    EXPECT_EQ(sg["resampled_fraction"].get<double>(), 0.0);  // adaptive off: nothing re-traced
    EXPECT_GT(sgAdaptive["pass_median_ms"].count("resample"), 0u);
}

TEST(UpsampleGpu, ViewsAuxAndTimingsReportTheResampling) {
    const fs::path dir =
        renderCornell("views", {"--frames", "3", "--trace-scale", "4", "--view", "resample"});
    for (const char* name : {"weight_sum.exr", "resample_mask.png", "final.png"})
        EXPECT_TRUE(fs::exists(dir / name)) << name;
    const nlohmann::json timings = nlohmann::json::parse(std::ifstream(dir / "timings.json"));
    ASSERT_TRUE(timings.contains("resampled_fraction"));
    const double fraction = timings["resampled_fraction"].get<double>();
    // The overlay is red exactly where the mask says a pixel was re-traced.
    const vct::ImageRgba8 overlay = vct::readPng(dir / "final.png");
    const vct::ImageRgba8 mask = vct::readPng(dir / "resample_mask.png");
    size_t masked = 0, red = 0;
    for (size_t i = 0; i < mask.pixels.size(); i += 4) {
        if (mask.pixels[i] < 128) continue;
        ++masked;
        red += overlay.pixels[i] == 255 && overlay.pixels[i + 1] == 0 && overlay.pixels[i + 2] == 0;
    }
    EXPECT_EQ(red, masked);
    EXPECT_NEAR(double(masked) / (160.0 * 90.0), fraction, 1e-6);
    std::printf("resample overlay: %zu re-traced pixels\n", masked);
    // The overlay must have something to show, or the checks above pass on an empty mask: measured 46
    // re-traced pixels of 14400 at frame 3 (lavapipe); at least 20.
    EXPECT_GE(masked, 20u) << "re-traced pixels in the overlay";

    const fs::path heat =
        renderCornell("weights_view", {"--frames", "2", "--trace-scale", "2", "--view", "weights"});
    EXPECT_TRUE(fs::exists(heat / "final.png"));
}

TEST(UpsampleGpu, BadUpsampleFlagsAreOneLineErrors) {
    for (std::vector<std::string> args : {std::vector<std::string>{"render", "--weights", "gaussian"},
                                          {"render", "--tau", "-1"},
                                          {"render", "--gamma", "1.5"},
                                          {"render", "--beta", "nan"},
                                          {"render", "--temporal", "maybe"},
                                          {"render", "--adaptive", "2"},
                                          {"render", "--kappa", "0"},
                                          {"render", "--camera-cut", "0"}}) {
        const auto r = vct::test::runVct(args);
        ASSERT_TRUE(r.exited()) << r.describe();
        EXPECT_EQ(r.exitCode, 2) << args[1] << ": " << r.describe();
        EXPECT_NE(r.err.find("--" + args[1].substr(2)), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

}  // namespace
