// What every `vct benchmark` mode shares: renderers measured side by side on one device, their frames
// interleaved in blocks, and their per-pass GPU timings as JSON.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "scene/scene.h"

namespace vct {

// One configuration of a benchmark: a scene, settings, and the renderer made from them.
struct BenchmarkRun {
    std::string name;
    const Scene* scene = nullptr;
    RenderSettings settings;
    std::unique_ptr<Renderer> renderer;
    std::string error;  // set when the configuration could not be made (reported, not measured)
};

// Renders `frames` fixed-step frames (1/60 s, from t = 0) of every run, taking turns in blocks of `block`
// frames: each run sees the machine's load over the whole measurement (ratios between runs stay fair on a
// shared CPU device) and runs a few frames in a row with its own data warm in the caches, as it would alone.
// Frames before `warmup` are left out of the timings. Prints progress on stderr for long runs.
// `frameInput` (optional) replaces the fixed-step frame of the scene camera (a camera path, a cut);
// `afterFrame` (optional) is called after each frame of each run, with the run's index (error curves: read
// the frame back).
struct FrameHooks {
    std::function<FrameInput(const BenchmarkRun& run, uint32_t frame, uint32_t warmup)> frameInput;
    std::function<void(size_t run, uint32_t frame)> afterFrame;
};
void renderInterleaved(std::vector<BenchmarkRun>& runs, uint32_t frames, uint32_t warmup, uint32_t block,
                       const FrameHooks& hooks = {});

// The median of one pass's GPU time (0 when the renderer has no such pass).
double passMedian(const Renderer& renderer, const std::string& pass);

// Per-pass medians, frame median and frame rate of a renderer: {"pass_median_ms": {...}, "frame_median_ms",
// "fps"}, plus the settings it ran with.
nlohmann::json timingJson(const Renderer& renderer);

// Markdown table pieces shared by the modes: the header (leading columns, then one per pass) and a row's pass
// cells (" 1.23 |" per pass, then a newline).
std::string passTableHeader(const std::string& leadingColumns, const std::vector<std::string>& passes);
std::string passTableCells(const Renderer& renderer, const std::vector<std::string>& passes);

// Writes DIR/NAME.json and DIR/NAME.md (a caption line and a Markdown table) and prints the table.
void writeBenchmarkReport(const std::filesystem::path& dir, const std::string& name,
                          const nlohmann::json& report, const std::string& caption, const std::string& table);

}  // namespace vct
