#include "report/timings_json.h"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/safe_write.h"
#include "render/renderer.h"
#include "report/settings_json.h"

namespace vct {

TimingReport::VoxelStorage voxelStorageReport(Renderer& renderer) {
    TimingReport::VoxelStorage storage;
    const VoxelGrid* grid = renderer.voxelGrid();
    if (!grid) return storage;
    storage.resolution = grid->resolution();
    storage.bricks = grid->bricks().brickCount();
    storage.brickSlots = uint32_t(grid->bricks().map.size());
    storage.bytes = grid->memory().bytes;
    storage.denseBytes = grid->memory().denseBytes;
    storage.regions = grid->regions().components;
    storage.labelledRegions = grid->regions().labelled;
    storage.regionsUsed = grid->usesRegions();
    return storage;
}

void writeTimingsJson(const std::filesystem::path& path, const TimingReport& report) {
    nlohmann::json passes = nlohmann::json::array();
    for (const vk::PassTiming& pass : report.passes)
        passes.push_back({{"name", pass.name},
                          {"median_ms", pass.medianMs},
                          {"p95_ms", pass.p95Ms},
                          {"min_ms", pass.minMs},
                          {"runs", pass.runs}});
    nlohmann::json json = {{"device", report.device},
                           {"size", {report.width, report.height}},
                           {"frames", report.frames},
                           {"warmup", report.warmup},
                           {"anisotropy", report.anisotropy},
                           {"passes", passes},
                           {"frame_median_ms", report.frame.medianMs},
                           {"fps", report.frame.medianMs > 0.0 ? 1000.0 / report.frame.medianMs : 0.0},
                           {"settings", settingsJson(report.settings)},
                           {"resampled_fraction", report.resampledFraction}};
    if (report.voxels.resolution > 0)
        json["voxel_storage"] = {{"resolution", report.voxels.resolution},
                                 {"bricks", report.voxels.bricks},
                                 {"brick_slots", report.voxels.brickSlots},
                                 {"bytes", report.voxels.bytes},
                                 {"dense_bytes", report.voxels.denseBytes},
                                 {"regions", report.voxels.regions},
                                 {"labelled_regions", report.voxels.labelledRegions},
                                 {"regions_end_cones", report.voxels.regionsUsed}};
    json["shadow_map"] = {{"texels", report.shadowTexels},
                          {"redrawn_texels_last_frame", report.shadowTexelsRedrawn}};
    json["gbuffer"] = {{"pixels", uint64_t(report.width) * report.height},
                       {"redrawn_pixels_last_frame", report.gbufferPixelsRedrawn}};
    json["direct"] = {{"partial_last_frame", report.directPartial},
                      {"dispatched_pixels_last_frame", report.directPixelsDispatched}};
    writeTextReplacing(path, json.dump(2) + "\n");  // replaces a planted symlink instead of following it
}

std::string formatTimingTable(const TimingReport& report) {
    std::string table;
    char line[160];
    // "ran": in how many of the timed frames the pass had work; a skipped frame counts as 0 ms (voxel passes
    // when nothing in the scene changed).
    std::snprintf(line, sizeof(line), "%-12s %10s %10s %10s %6s\n", "pass", "median ms", "p95 ms", "min ms",
                  "ran");
    table += line;
    for (const vk::PassTiming& pass : report.passes) {
        std::snprintf(line, sizeof(line), "%-12s %10.3f %10.3f %10.3f %6zu\n", pass.name.c_str(),
                      pass.medianMs, pass.p95Ms, pass.minMs, pass.runs);
        table += line;
    }
    std::snprintf(line, sizeof(line), "%-12s %10.3f %10.3f %10.3f %6zu\n", "frame", report.frame.medianMs,
                  report.frame.p95Ms, report.frame.minMs, report.frame.samples);
    table += line;
    if (report.frame.medianMs > 0.0) {
        std::snprintf(line, sizeof(line), "fps          %9.1f (1000 / frame median)\n",
                      1000.0 / report.frame.medianMs);
        table += line;
    }
    std::snprintf(line, sizeof(line), "re-traced    %9.2f%% of the pixels (last frame)\n",
                  100.0 * report.resampledFraction);
    table += line;
    const TimingReport::VoxelStorage& v = report.voxels;
    if (v.resolution > 0 && v.brickSlots > 0 && v.denseBytes > 0) {
        std::snprintf(line, sizeof(line),
                      "voxels       %u^3: %u of %u bricks (%.1f%%), %.1f MiB (dense %.1f MiB: %.1f%%)\n",
                      v.resolution, v.bricks, v.brickSlots, 100.0 * v.bricks / v.brickSlots,
                      double(v.bytes) / 1048576.0, double(v.denseBytes) / 1048576.0,
                      100.0 * double(v.bytes) / double(v.denseBytes));
        table += line;
        std::snprintf(
            line, sizeof(line), "regions      %u of empty voxels, %u labelled: %s\n", v.regions,
            v.labelledRegions,
            v.regionsUsed ? "cones end where they pass into another" : "the closure box closes them");
        table += line;
    }
    return table;
}

}  // namespace vct
