// The modes of `vct benchmark` beyond the default (upsampling, in benchmark_command.cpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/cli.h"
#include "app/cli/session.h"
#include "scene/camera_path.h"

namespace vct {

// How long each configuration runs: frames, the warm-up left out of the timings, frames per turn.
struct BenchmarkFrames {
    uint32_t frames = 64;
    uint32_t warmup = 10;
    uint32_t block = 8;
};

// scenes: the default configuration (session.settings) on several scenes at one size: frame and per-pass
// medians, and each frame median over cornell's. Writes DIR/scenes.json and DIR/scenes.md.
int runScenesBenchmark(const ParsedArgs& args, const SessionOptions& session, const BenchmarkFrames& frames,
                       const std::filesystem::path& outDir);

// scaling: the default configuration on one scene against pixel count (160×90 … 1280×720, default voxels) and
// voxel resolution (32³ … 256³ at --size). Writes DIR/scaling.json and DIR/scaling.md.
int runScalingBenchmark(const ParsedArgs& args, const SessionOptions& session, const BenchmarkFrames& frames,
                        const std::filesystem::path& outDir);

// report: per scene of the report list and per camera (static, moving along the scene's path, cut halfway),
// the reference and trace scales 2/4 × bilinear/normal/sg × adaptive off/on (and a τ sweep on the moving
// camera), with errors after every frame. Writes DIR/report.json and DIR/report.md
// (app/bench/benchmark_report.cpp).
int runReportBenchmark(const ParsedArgs& args, const SessionOptions& session, const BenchmarkFrames& frames,
                       const std::filesystem::path& outDir);

// study: Tokuyoshi 2015's parameter study (Fig. 6; docs/design.md §8.4): β × κ for sg, σ_n for normal, the
// diffuse lobe sharpness, spatial upsampling only, errors per material class. Writes DIR/study.json and
// DIR/study.md.
int runStudyBenchmark(const ParsedArgs& args, const SessionOptions& session, const BenchmarkFrames& frames,
                      const std::filesystem::path& outDir);

// A scene of the report list (scenes/report_scenes.json): a short name, the built-in name or glTF path, and
// its camera path when it has one.
struct ReportScene {
    std::string name;
    std::string scene;
    std::optional<CameraPath> path;
};
// The report list's scenes (--report-scenes FILE, filtered by --scenes A,B); shared glTF models missing under
// --scenes-dir are skipped with a note.
std::vector<ReportScene> reportScenes(const ParsedArgs& args);

}  // namespace vct
