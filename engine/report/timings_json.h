// timings.json: per-pass GPU timings (median / p95 / min over the frames after the warm-up).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/settings.h"
#include "vk/timer.h"

namespace vct {

class Renderer;

struct TimingReport {
    std::string device;
    uint32_t width = 0, height = 0;
    uint32_t frames = 0, warmup = 0;
    uint32_t anisotropy = 0;  // material textures' anisotropic filtering level in use (0: off)
    RenderSettings settings;  // what the frames were rendered with (after the renderer's choices)
    std::vector<vk::PassTiming> passes;
    vk::PassTiming frame;
    float resampledFraction = 0.0f;  // share of the pixels re-traced in the last frame (adaptive re-tracing)
    // The voxel grid's sparse storage (docs/design.md §5.10); resolution 0: no grid (GI off).
    struct VoxelStorage {
        uint32_t resolution = 0;
        uint32_t bricks = 0, brickSlots = 0;  // allocated, and (N / VCT_VOXEL_BRICK)³
        uint64_t bytes = 0, denseBytes = 0;   // device memory, and what dense N³ storage would take
        // The static grid's closed regions (render/voxel_regions.h): 6-connected components of the empty voxels,
        // how many got a label, and whether cones end where they pass into another.
        uint32_t regions = 0, labelledRegions = 0;
        bool regionsUsed = false;
    } voxels;
    // The shadow map (docs/design.md §5.8): its texels, and how many of them the last frame redrew (all, a
    // rectangle where only instances moved, or 0 when nothing did).
    uint64_t shadowTexels = 0, shadowTexelsRedrawn = 0;
    // Whether the last frame recomputed the direct light only where moving instances can change it (§5.8).
    bool directPartial = false;
    uint64_t directPixelsDispatched = 0;  // in the last frame: all, a rectangle when partial, 0 when skipped
    // The G-buffer's pixels the last frame redrew (all, a rectangle where only instances moved, 0 when reused).
    uint64_t gbufferPixelsRedrawn = 0;
};

// The renderer's voxel storage for the report (all zero without a grid).
TimingReport::VoxelStorage voxelStorageReport(Renderer& renderer);

void writeTimingsJson(const std::filesystem::path& path, const TimingReport& report);
// A fixed-width table for the terminal.
std::string formatTimingTable(const TimingReport& report);

}  // namespace vct
