// `vct benchmark --mode scenes|scaling` (app/bench/benchmark_scenes.cpp, app/bench/benchmark_scaling.cpp): one entry per
// scene or point with finite per-pass medians, frame ratios that add up, the report files, and bad modes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace {

namespace fs = std::filesystem;

TEST(BenchmarkModes, ScenesReportsEveryRequestedScene) {
    const fs::path dir = vct::test::freshOutputDir("benchmark_modes/scenes");
    const auto r = vct::test::runVct({"benchmark", "--mode", "scenes", "--scenes", "cornell,plane", "--size",
                                      "64x36", "--voxels", "32", "--frames", "5", "--warmup", "1", "--block",
                                      "2", "--validate", "--out", dir.string()});
    ASSERT_TRUE(r.exited() && r.exitCode == 0) << r.describe();
    ASSERT_TRUE(fs::is_regular_file(dir / "scenes.md"));
    const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "scenes.json"));
    ASSERT_EQ(report["scenes"].size(), 2u) << report.dump(2);
    EXPECT_EQ(report["scenes"][0]["name"], "cornell");
    EXPECT_EQ(report["scenes"][1]["name"], "plane");
    const double cornell = report["scenes"][0]["frame_median_ms"].get<double>();
    for (const auto& scene : report["scenes"]) {
        const double frame = scene["frame_median_ms"].get<double>();
        EXPECT_TRUE(std::isfinite(frame) && frame > 0.0) << scene.dump();
        EXPECT_NEAR(scene["over_cornell"].get<double>(), frame / cornell, 1e-9) << scene.dump();
        EXPECT_EQ(scene["settings"]["trace_scale"], 4) << scene.dump();
        for (const auto& [pass, ms] : scene["pass_median_ms"].items())
            EXPECT_TRUE(std::isfinite(ms.get<double>()) && ms.get<double>() >= 0.0) << pass;
    }
    // The static plane reuses its shadow map and G-buffer: they cost it nothing after the first frames.
    EXPECT_EQ(report["scenes"][1]["pass_median_ms"]["gbuffer"].get<double>(), 0.0);
    EXPECT_GT(report["scenes"][0]["pass_median_ms"]["gbuffer"].get<double>(), 0.0);  // cornell's cube moves
}

TEST(BenchmarkModes, BadModeAndMissingSceneAreUsageErrors) {
    const fs::path dir = vct::test::freshOutputDir("benchmark_modes/bad");
    const auto mode = vct::test::runVct({"benchmark", "--mode", "fastest", "--out", dir.string()});
    ASSERT_TRUE(mode.exited());
    EXPECT_EQ(mode.exitCode, 2) << mode.describe();
    EXPECT_NE(mode.err.find("--mode 'fastest'"), std::string::npos) << mode.err;
    const auto scene =
        vct::test::runVct({"benchmark", "--mode", "scenes", "--scenes", "cornell,/no/such.gltf", "--size",
                           "64x36", "--frames", "3", "--warmup", "1", "--out", dir.string()});
    ASSERT_TRUE(scene.exited());
    EXPECT_NE(scene.exitCode, 0) << scene.describe();
    EXPECT_NE(scene.err.find("such.gltf"), std::string::npos) << scene.err;
}

}  // namespace
