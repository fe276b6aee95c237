// vct benchmark --mode scaling: how each pass's cost grows with the pixel count (160×90 … 1280×720 at the
// default voxel grid) and with the voxel resolution (32³ … 256³ at --size), the default configuration on one
// scene, all configurations interleaved in blocks in one run (app/bench/benchmark_run.h). A configuration the device
// cannot make is recorded with its error instead of timings. benchmarks/plot_scaling.py plots the JSON.
#include <cstdio>

#include "app/bench/benchmark_modes.h"
#include "app/bench/benchmark_run.h"
#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace vct {

int runScalingBenchmark(const ParsedArgs& args, const SessionOptions& session, const BenchmarkFrames& timing,
                        const std::filesystem::path& outDir) {
    (void)args;
    const Scene scene = loadScene(session.scene);
    struct Point {
        const char* sweep;               // "pixels" or "voxels"
        uint32_t width, height, voxels;  // voxels 0: the device's default
    };
    std::vector<Point> points;
    for (auto [w, h] : {std::pair{160u, 90u}, {320u, 180u}, {640u, 360u}, {1280u, 720u}})
        points.push_back({"pixels", w, h, session.settings.voxelResolution});
    for (uint32_t n : {32u, 64u, 128u, 256u})
        points.push_back({"voxels", session.settings.width, session.settings.height, n});

    nlohmann::json report;
    std::string table;
    {
        vk::Context context(session.context);
        std::printf("device: %s\n", context.deviceName().c_str());
        std::vector<BenchmarkRun> runs;
        for (const Point& point : points) {
            BenchmarkRun run{std::string(point.sweep) + " " + std::to_string(point.width) + "x" +
                                 std::to_string(point.height) + " N=" + std::to_string(point.voxels),
                             &scene, session.settings, nullptr, ""};
            run.settings.width = point.width;
            run.settings.height = point.height;
            run.settings.voxelResolution = point.voxels;
            try {
                run.renderer = std::make_unique<Renderer>(context, scene, run.settings);
            } catch (const std::exception& e) {
                run.error = e.what();
                std::fprintf(stderr, "note: %s: %s (recorded, not measured)\n", run.name.c_str(), e.what());
            }
            runs.push_back(std::move(run));
        }
        renderInterleaved(runs, timing.frames, timing.warmup, timing.block);

        report = {{"device", context.deviceName()}, {"scene", session.scene},
                  {"frames", timing.frames},        {"warmup", timing.warmup},
                  {"block", timing.block},          {"points", nlohmann::json::array()}};
        std::vector<std::string> passes;
        for (const BenchmarkRun& run : runs)
            if (run.renderer && passes.empty())
                for (const vk::PassTiming& pass : run.renderer->timer().passStats())
                    passes.push_back(pass.name);
        table = passTableHeader("sweep|size|voxels|frame ms", passes);
        for (size_t i = 0; i < runs.size(); ++i) {
            const BenchmarkRun& run = runs[i];
            nlohmann::json entry = run.renderer ? timingJson(*run.renderer) : nlohmann::json::object();
            entry["sweep"] = points[i].sweep;
            entry["width"] = points[i].width;
            entry["height"] = points[i].height;
            entry["pixels"] = uint64_t(points[i].width) * points[i].height;
            // The resolution the renderer chose (0 requested: the device's default).
            entry["voxels"] = run.renderer ? run.renderer->settings().voxelResolution : points[i].voxels;
            if (!run.error.empty()) entry["error"] = run.error;
            report["points"].push_back(entry);
            char cells[160];
            std::snprintf(cells, sizeof(cells), "| %s | %ux%u | %u³ |", points[i].sweep, points[i].width,
                          points[i].height, entry["voxels"].get<uint32_t>());
            table += cells;
            if (!run.renderer) {
                table += " failed: " + run.error + " |\n";
                continue;
            }
            std::snprintf(cells, sizeof(cells), " %.2f |", run.renderer->timer().frameStats().medianMs);
            table += cells + passTableCells(*run.renderer, passes);
        }
    }
    checkValidation(session);
    char caption[300];
    std::snprintf(
        caption, sizeof(caption),
        "Device: %s, scene %s, default configuration, %u frames in blocks of %u (medians after %u warm-up "
        "frames, ms).",
        report["device"].get<std::string>().c_str(), session.scene.c_str(), timing.frames, timing.block,
        timing.warmup);
    writeBenchmarkReport(outDir, "scaling", report, caption, table);
    return 0;
}

}  // namespace vct
