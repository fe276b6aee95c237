// The vct program end to end: `vct render` on the built-in cornell scene (exit status, images, timings.json),
// the informational commands, and every glTF sample model in shared/scenes. Renders are small (160x90, a few
// frames) because CI runs them on lavapipe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "hostile_util.h"
#include "io/image_io.h"
#include "scene/scene.h"
#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::RunResult;

constexpr uint32_t kWidth = 160, kHeight = 90;

// Luminance of every pixel of an RGBA float image.
std::vector<float> luminances(const ImageRgba32f& image) {
    std::vector<float> lum(size_t(image.width) * image.height);
    for (size_t i = 0; i < lum.size(); ++i)
        lum[i] = test::luminance(image.pixels[4 * i], image.pixels[4 * i + 1], image.pixels[4 * i + 2]);
    return lum;
}

// ---- vct render on the cornell scene: one render per test process, shared by the tests below ----

class RenderCornell : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        // Per process: ctest runs every test in its own process, possibly several at once.
        dir_ = new fs::path(test::freshOutputDir("render_cli/cornell-" + std::to_string(getpid())));
        run_ = new RunResult(test::runVct({"render", "--scene", "cornell", "--size", "160x90", "--frames",
                                           "4", "--out", dir_->string(), "--validate"}));
        std::cout << "vct render cornell 160x90 x4 --validate: " << run_->seconds << " s\n";
    }
    static void TearDownTestSuite() {
        // Kept for inspection when something failed.
        if (!::testing::UnitTest::GetInstance()->Failed()) fs::remove_all(*dir_);
        delete run_;
        delete dir_;
        run_ = nullptr;
        dir_ = nullptr;
    }
    void SetUp() override { ASSERT_TRUE(run_->exited() && run_->exitCode == 0) << run_->describe(); }

    static fs::path* dir_;
    static RunResult* run_;
};
fs::path* RenderCornell::dir_ = nullptr;
RunResult* RenderCornell::run_ = nullptr;

TEST_F(RenderCornell, ExitsCleanlyWithoutValidationMessages) {
    EXPECT_EQ(run_->err.find("validation"), std::string::npos) << run_->err;
    EXPECT_EQ(run_->err.find("error"), std::string::npos) << run_->err;
    EXPECT_NE(run_->out.find("device:"), std::string::npos) << run_->out;
    for (const char* file : {"final.png", "final.exr", "timings.json"})
        EXPECT_TRUE(fs::is_regular_file(*dir_ / file)) << file;
}

TEST_F(RenderCornell, PngHasTheRequestedSizeAndIsNotBlank) {
    ImageRgba8 png = readPng(*dir_ / "final.png");
    ASSERT_EQ(png.width, kWidth);
    ASSERT_EQ(png.height, kHeight);
    ASSERT_EQ(png.pixels.size(), size_t(kWidth) * kHeight * 4);
    uint8_t lo = 255, hi = 0;
    for (size_t i = 0; i < png.pixels.size(); i += 4) {
        for (int c = 0; c < 3; ++c) {
            lo = std::min(lo, png.pixels[i + size_t(c)]);
            hi = std::max(hi, png.pixels[i + size_t(c)]);
        }
        EXPECT_EQ(png.pixels[i + 3], 255) << "alpha at pixel " << i / 4;
        if (png.pixels[i + 3] != 255) break;
    }
    // Tone-mapped: a lit wall reaches the bright end, a shadowed corner stays near black.
    EXPECT_GE(hi, 200);
    EXPECT_LE(lo, 30);
}

TEST_F(RenderCornell, ExrIsFiniteLitAndHasShadows) {
    ImageRgba32f exr = readExr(*dir_ / "final.exr");
    ASSERT_EQ(exr.width, kWidth);
    ASSERT_EQ(exr.height, kHeight);
    ASSERT_EQ(exr.pixels.size(), size_t(kWidth) * kHeight * 4);
    ASSERT_EQ(test::countNonFinite(exr.pixels), 0u) << "NaN or Inf in final.exr";
    for (float v : exr.pixels) ASSERT_GE(v, 0.0f) << "negative radiance in final.exr";

    std::vector<float> lum = luminances(exr);
    std::vector<float> sorted = lum;
    std::sort(sorted.begin(), sorted.end());
    const float lo = sorted.front(), hi = sorted.back();
    // The emissive light panel is far brighter than anything it lights (and tiny at this size): the 99th
    // percentile stands for "the brightest lit surfaces" instead of the maximum.
    const float bright = sorted[sorted.size() * 99 / 100];
    // The ambient term is 0.03 * albedo, so at most 0.03: ten times that is certainly direct light.
    constexpr float kAmbientMax = 0.03f;
    size_t dark = 0, lit = 0;
    for (float l : lum) {
        dark += l < 0.1f * bright;
        lit += l > 10.0f * kAmbientMax;
    }
    const double darkFraction = double(dark) / double(lum.size()),
                 litFraction = double(lit) / double(lum.size());
    std::cout << "cornell luminance: min " << lo << ", median " << sorted[sorted.size() / 2]
              << ", 99th percentile " << bright << ", max " << hi << "; " << 100.0 * litFraction
              << "% of pixels above " << 10.0f * kAmbientMax << ", " << 100.0 * darkFraction
              << "% below 10% of the 99th percentile\n";

    EXPECT_GT(hi - lo, 0.05f) << "the image is (nearly) constant";
    EXPECT_GT(bright, 0.5f) << "nothing is lit well above the ambient level";
    // A lit area, not just a few bright pixels...
    EXPECT_GT(litFraction, 0.03);
    // ...and a meaningful part of the frame in shadow (or outside the light's cone), but not all of it.
    EXPECT_GT(darkFraction, 0.10);
    EXPECT_LT(darkFraction, 0.97);
}

TEST_F(RenderCornell, TimingsJsonFollowsTheSchema) {
    json timings;
    {
        std::ifstream file(*dir_ / "timings.json");
        ASSERT_TRUE(file) << "cannot open timings.json";
        ASSERT_NO_THROW(timings = json::parse(file));
    }
    ASSERT_TRUE(timings.is_object()) << timings.dump(2);
    ASSERT_TRUE(timings.contains("device") && timings["device"].is_string()) << timings.dump(2);
    EXPECT_FALSE(timings["device"].get<std::string>().empty());

    ASSERT_TRUE(timings.contains("size") && timings["size"].is_array()) << timings.dump(2);
    ASSERT_EQ(timings["size"].size(), 2u);
    ASSERT_TRUE(timings["size"][0].is_number_integer() && timings["size"][1].is_number_integer());
    EXPECT_EQ(timings["size"][0].get<int64_t>(), kWidth);
    EXPECT_EQ(timings["size"][1].get<int64_t>(), kHeight);

    ASSERT_TRUE(timings.contains("frames") && timings["frames"].is_number_integer()) << timings.dump(2);
    EXPECT_EQ(timings["frames"].get<int64_t>(), 4);
    // Default warmup: min(10, frames / 4) (see vct render --help).
    ASSERT_TRUE(timings.contains("warmup") && timings["warmup"].is_number_integer()) << timings.dump(2);
    EXPECT_EQ(timings["warmup"].get<int64_t>(), 1);

    ASSERT_TRUE(timings.contains("frame_median_ms") && timings["frame_median_ms"].is_number())
        << timings.dump(2);
    const double frameMedian = timings["frame_median_ms"].get<double>();
    EXPECT_GT(frameMedian, 0.0);

    ASSERT_TRUE(timings.contains("passes") && timings["passes"].is_array()) << timings.dump(2);
    std::set<std::string> names;
    for (const json& pass : timings["passes"]) {
        ASSERT_TRUE(pass.is_object()) << pass.dump();
        for (const char* key : {"median_ms", "p95_ms", "min_ms"})
            ASSERT_TRUE(pass.contains(key) && pass[key].is_number()) << key << " in " << pass.dump();
        ASSERT_TRUE(pass.contains("name") && pass["name"].is_string()) << pass.dump();
        const std::string name = pass["name"].get<std::string>();
        EXPECT_TRUE(names.insert(name).second) << "pass '" << name << "' listed twice";
        const double median = pass["median_ms"].get<double>(), p95 = pass["p95_ms"].get<double>(),
                     min = pass["min_ms"].get<double>();
        EXPECT_GT(median, 0.0) << name;
        EXPECT_GT(min, 0.0) << name;
        EXPECT_LE(min, median) << name;
        EXPECT_LE(median, p95) << name;
        // Each frame's time spans all of its passes, so the frame median bounds every pass median.
        EXPECT_LE(median, frameMedian * (1.0 + 1e-9)) << name;
    }
    for (const char* required : {"shadow", "gbuffer", "direct", "composite"})
        EXPECT_TRUE(names.count(required)) << "no '" << required << "' pass in " << timings["passes"].dump();

    // The run gave no GI flags: the defaults run the method (issue 8) — a 1/4-resolution trace, upsampled with
    // SG lobe weights and history, low-weight pixels re-traced — and timings.json says so.
    for (const char* required : {"voxelize", "inject", "mips", "trace", "upsample", "resample"})
        EXPECT_TRUE(names.count(required)) << "no '" << required << "' pass in " << timings["passes"].dump();
    ASSERT_TRUE(timings.contains("settings") && timings["settings"].is_object()) << timings.dump(2);
    const json& settings = timings["settings"];
    EXPECT_EQ(settings.value("trace_scale", 0), 4) << settings.dump();
    EXPECT_EQ(settings.value("weights", ""), "sg") << settings.dump();
    EXPECT_TRUE(settings.value("temporal", false)) << settings.dump();
    EXPECT_TRUE(settings.value("adaptive", false)) << settings.dump();
    EXPECT_TRUE(settings.value("gi", false)) << settings.dump();
    ASSERT_TRUE(timings.contains("fps") && timings["fps"].is_number()) << timings.dump(2);
    EXPECT_NEAR(timings["fps"].get<double>(), 1000.0 / frameMedian, 1e-6 * timings["fps"].get<double>());
}

// ---- informational commands ----

// The built-in hall (40 m, a sun through roof openings, thin walls): renders clean and finite, the sun reaches
// the floor through the openings and bounced light lights the rest (measured at 160x90, 64³, under the default
// sky: 4.7 % of the pixels above luminance 0.8; 94 % get no direct light, 84 % of all pixels are lit above 0.02
// by indirect light alone; mean luminance 0.156 with indirect light against 0.054 direct: 2.9x).
TEST(RenderCli, HallIsLitByTheSunThroughItsOpeningsAndByBouncedLight) {
    const fs::path dir = test::freshOutputDir("render_cli/hall");
    RunResult r = test::runVct({"render", "--scene", "hall", "--size", "160x90", "--frames", "2", "--aux",
                                "--out", dir.string(), "--validate"});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
    const ImageRgba32f final = readExr(dir / "final.exr"), direct = readExr(dir / "direct.exr");
    ASSERT_EQ(test::countNonFinite(final.pixels), 0u);
    const std::vector<float> lum = luminances(final), directLum = luminances(direct);
    ASSERT_EQ(lum.size(), directLum.size());
    size_t sunlit = 0, indirectOnly = 0;
    double sumFinal = 0.0, sumDirect = 0.0;
    for (size_t i = 0; i < lum.size(); ++i) {
        sunlit += lum[i] > 0.8f ? 1 : 0;
        indirectOnly += (directLum[i] < 1e-4f && lum[i] > 0.02f) ? 1 : 0;
        sumFinal += lum[i];
        sumDirect += directLum[i];
    }
    const double n = double(lum.size());
    EXPECT_GE(sunlit / n, 0.02);
    EXPECT_LE(sunlit / n, 0.15);
    EXPECT_GE(indirectOnly / n, 0.6) << "pixels lit by indirect light alone";
    EXPECT_GE(sumFinal, 2.0 * sumDirect) << "mean luminance with indirect light against direct light alone";
}

// Issue 20: a scene without a camera rendered (or path-traced) along --camera-path does not claim a default
// camera: the path is the camera, and the note says so. Without the path the default camera's note stays.
TEST(RenderCli, CameraPathReplacesTheDefaultCameraNote) {
    const fs::path dir = test::freshOutputDir("render_cli/camera-path-note");
    const fs::path scene = hostile::writeGltf(dir, hostile::triangleScene());
    const fs::path path = dir / "path.json";
    test::writeTextFile(path,
                        R"({"keys": [{"time": 0, "position": [0.3, 0.3, 2], "target": [0.3, 0.3, 0]}]})");
    for (bool withPath : {false, true}) {
        const std::vector<std::string> extra =
            withPath ? std::vector<std::string>{"--camera-path", path.string()} : std::vector<std::string>{};
        RunResult render = test::runVct(hostile::renderArgs(scene, dir / "render", extra));
        ASSERT_TRUE(render.exited() && render.exitCode == 0) << render.describe();
        std::vector<std::string> referenceArgs = {"reference", "--scene", scene.string(),
                                                  "--size",    "16x9",    "--spp",
                                                  "1",         "--out",   (dir / "reference").string()};
        referenceArgs.insert(referenceArgs.end(), extra.begin(), extra.end());
        RunResult reference = test::runVct(referenceArgs);
        ASSERT_TRUE(reference.exited() && reference.exitCode == 0) << reference.describe();
        for (const RunResult* r : {&render, &reference}) {
            EXPECT_EQ(r->out.find(kDefaultCameraNote) != std::string::npos, !withPath) << r->out;
            EXPECT_EQ(r->out.find("the camera follows " + path.string()) != std::string::npos, withPath)
                << r->out;
        }
    }
}

TEST(RenderCli, ScenesListsCornell) {
    RunResult r = test::runVct({"scenes"});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    bool found = false;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) found = found || line.rfind("cornell", 0) == 0;
    EXPECT_TRUE(found) << "no line starting with 'cornell' in:\n" << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(RenderCli, HelpExitsZero) {
    RunResult r = test::runVct({"--help"});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    EXPECT_NE(r.out.find("render"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("scenes"), std::string::npos) << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(RenderCli, RenderHelpExitsZero) {
    RunResult r = test::runVct({"render", "--help"});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    for (const char* flag : {"--scene", "--size", "--frames", "--out", "--validate"})
        EXPECT_NE(r.out.find(flag), std::string::npos) << flag << " not in:\n" << r.out;
    EXPECT_TRUE(r.err.empty()) << r.err;
}

// ---- every glTF sample model in shared/scenes (<model>/glTF/*.gltf) ----

const fs::path kSharedScenes = VCT_SHARED_SCENES;

std::vector<std::string> sharedModels() {
    std::vector<std::string> models;
    std::error_code ec;
    if (fs::is_directory(kSharedScenes, ec)) {
        for (const fs::directory_entry& model : fs::directory_iterator(kSharedScenes, ec)) {
            if (!fs::is_directory(model.path() / "glTF", ec)) continue;
            for (const fs::directory_entry& file : fs::directory_iterator(model.path() / "glTF", ec))
                if (file.path().extension() == ".gltf")
                    models.push_back(fs::relative(file.path(), kSharedScenes, ec).generic_string());
        }
    }
    std::sort(models.begin(), models.end());
    // One placeholder so the absence of the folder is a visible skip, not a silently empty suite.
    if (models.empty()) models.push_back("");
    return models;
}

std::string modelTestName(const ::testing::TestParamInfo<std::string>& info) {
    if (info.param.empty()) return "NoSharedScenes";
    std::string name = fs::path(info.param).stem().string();
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name + "_" + std::to_string(info.index);
}

class RenderSharedModel : public ::testing::TestWithParam<std::string> {};

TEST_P(RenderSharedModel, RendersWithValidationAndFiniteOutput) {
    if (GetParam().empty())
        GTEST_SKIP() << "no glTF models under " << kSharedScenes << " (shared/scenes absent)";
    const fs::path model = kSharedScenes / GetParam();
    ASSERT_TRUE(fs::is_regular_file(model)) << model;
    const fs::path dir = test::freshOutputDir("render_cli/models/" + model.stem().string());
    RunResult r = test::runVct({"render", "--scene", model.string(), "--size", "160x90", "--frames", "2",
                                "--out", dir.string(), "--validate"});
    std::cout << "vct render " << model.filename().string() << " 160x90 x2 --validate: " << r.seconds
              << " s\n";
    RecordProperty("render_seconds", std::to_string(r.seconds));
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;

    ImageRgba8 png = readPng(dir / "final.png");
    EXPECT_EQ(png.width, kWidth);
    EXPECT_EQ(png.height, kHeight);
    ImageRgba32f exr = readExr(dir / "final.exr");
    ASSERT_EQ(exr.width, kWidth);
    ASSERT_EQ(exr.height, kHeight);
    EXPECT_EQ(test::countNonFinite(exr.pixels), 0u) << "NaN or Inf in " << (dir / "final.exr");
    // The model is in view and shaded: not a single flat colour.
    std::vector<float> lum = luminances(exr);
    auto [lo, hi] = std::minmax_element(lum.begin(), lum.end());
    EXPECT_GT(*hi - *lo, 0.01f) << "final.exr is (nearly) constant";
}

INSTANTIATE_TEST_SUITE_P(SharedScenes, RenderSharedModel, ::testing::ValuesIn(sharedModels()), modelTestName);

}  // namespace
}  // namespace vct
