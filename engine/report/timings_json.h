// timings.json: per-pass GPU timings (median / p95 / min over the frames after the warm-up).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/settings.h"
#include "vk/timer.h"

namespace vct {

struct TimingReport {
    std::string device;
    uint32_t width = 0, height = 0;
    uint32_t frames = 0, warmup = 0;
    uint32_t anisotropy = 0;  // material textures' anisotropic filtering level in use (0: off)
    RenderSettings settings;  // what the frames were rendered with (after the renderer's choices)
    std::vector<vk::PassTiming> passes;
    vk::PassTiming frame;
    float resampledFraction = 0.0f;  // share of the pixels re-traced in the last frame (adaptive re-tracing)
};

void writeTimingsJson(const std::filesystem::path& path, const TimingReport& report);
// A fixed-width table for the terminal.
std::string formatTimingTable(const TimingReport& report);

}  // namespace vct
