#include "app/bench/benchmark_run.h"

#include <chrono>
#include <cstdio>
#include <fstream>

#include "app/cli/progress_line.h"
#include "core/error.h"
#include "io/safe_write.h"
#include "report/settings_json.h"

namespace vct {

void renderInterleaved(std::vector<BenchmarkRun>& runs, uint32_t frames, uint32_t warmup, uint32_t block,
                       const FrameHooks& hooks) {
    block = std::max(block, 1u);
    size_t live = 0;
    for (const BenchmarkRun& run : runs) live += run.renderer ? 1 : 0;
    const uint64_t total = uint64_t(frames) * live;
    uint64_t done = 0;
    const auto start = std::chrono::steady_clock::now();
    bool progress = false;
    for (uint32_t first = 0; first < frames; first += block) {
        const uint32_t last = std::min(frames, first + block);
        for (size_t index = 0; index < runs.size(); ++index) {
            BenchmarkRun& run = runs[index];
            if (!run.renderer) continue;
            for (uint32_t frame = first; frame < last; ++frame, ++done) {
                run.renderer->render(hooks.frameInput ? hooks.frameInput(run, frame, warmup)
                                                      : fixedStepFrame(*run.scene, frame, warmup));
                if (hooks.afterFrame) hooks.afterFrame(index, frame);
            }
            // A progress line once the run has taken a few seconds (stderr: the tables stay clean on stdout).
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (seconds > 3.0) {
                // A bar, the share done and the time left at the rate so far.
                const int percent = int(100 * done / std::max<uint64_t>(total, 1));
                const double left = done ? seconds * double(total - done) / double(done) : 0.0;
                char detail[96];
                std::snprintf(detail, sizeof(detail), "of %llu frames, %.0f s, ~%.0f s left ",
                              static_cast<unsigned long long>(total), seconds, left);
                printProgressLine("benchmark", percent, detail);
                progress = true;
            }
        }
    }
    if (progress) std::fprintf(stderr, "\n");
}

double passMedian(const Renderer& renderer, const std::string& pass) {
    for (const vk::PassTiming& timing : renderer.timer().passStats())
        if (timing.name == pass) return timing.medianMs;
    return 0.0;
}

nlohmann::json timingJson(const Renderer& renderer) {
    nlohmann::json passes = nlohmann::json::object();
    for (const vk::PassTiming& timing : renderer.timer().passStats()) passes[timing.name] = timing.medianMs;
    const double frameMs = renderer.timer().frameStats().medianMs;
    return {{"pass_median_ms", passes},
            {"frame_median_ms", frameMs},
            {"fps", frameMs > 0.0 ? 1000.0 / frameMs : 0.0},
            {"settings", settingsJson(renderer.settings())}};
}

std::string passTableHeader(const std::string& leadingColumns, const std::vector<std::string>& passes) {
    std::string header = "|", rule = "|";
    std::string column;
    for (char c : leadingColumns + "|") {
        if (c != '|') {
            column += c;
            continue;
        }
        header += " " + column + " |";
        rule += "---|";
        column.clear();
    }
    for (const std::string& pass : passes) {
        header += " " + pass + " |";
        rule += "---|";
    }
    return header + "\n" + rule + "\n";
}

std::string passTableCells(const Renderer& renderer, const std::vector<std::string>& passes) {
    std::string cells;
    char cell[32];
    for (const std::string& pass : passes) {
        std::snprintf(cell, sizeof(cell), " %.2f |", passMedian(renderer, pass));
        cells += cell;
    }
    return cells + "\n";
}

void writeBenchmarkReport(const std::filesystem::path& dir, const std::string& name,
                          const nlohmann::json& report, const std::string& caption,
                          const std::string& table) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw Error("cannot create output directory '" + dir.string() + "': " + error.message());
    const std::filesystem::path json = dir / (name + ".json"), md = dir / (name + ".md");
    writeTextReplacing(json, report.dump(2) + "\n");
    writeTextReplacing(md, caption + "\n\n" + table);
    std::printf("%s", table.c_str());
    std::printf("wrote %s, %s\n", json.c_str(), md.c_str());
}

}  // namespace vct
