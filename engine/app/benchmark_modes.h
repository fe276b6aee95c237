// The modes of `vct benchmark` beyond the default (upsampling, in benchmark_command.cpp).
#pragma once

#include <cstdint>
#include <filesystem>

#include "app/cli.h"
#include "app/session.h"

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

}  // namespace vct
