// vct benchmark --mode scenes: the default configuration on the built-in rooms and on real glTF content, in one
// run (issue 8: a cost that appears only with 2k textures is still ours). Every scene gets its own Scene and
// Renderer on one Vulkan device; frames are interleaved in blocks (app/bench/benchmark_run.h).
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "app/bench/benchmark_modes.h"
#include "app/bench/benchmark_run.h"
#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace vct {

namespace {

// The glTF models under `dir`: DIR/NAME/glTF/*.gltf (the Khronos sample layout), DIR/NAME/*.gltf|glb, sorted.
std::vector<std::string> gltfModelsUnder(const std::filesystem::path& dir) {
    std::vector<std::string> models;
    std::error_code error;
    if (!std::filesystem::is_directory(dir, error)) return models;
    for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
        if (!entry.is_directory()) continue;
        for (const std::filesystem::path& folder : {entry.path() / "glTF", entry.path()}) {
            std::vector<std::string> found;
            for (const auto& file : std::filesystem::directory_iterator(folder, error)) {
                const std::string ext = file.path().extension().string();
                if (file.is_regular_file() && (ext == ".gltf" || ext == ".glb"))
                    found.push_back(file.path().string());
            }
            std::sort(found.begin(), found.end());
            if (!found.empty()) {
                models.push_back(found.front());
                break;
            }
        }
    }
    std::sort(models.begin(), models.end());
    return models;
}

std::vector<std::string> sceneList(const ParsedArgs& args) {
    std::vector<std::string> scenes;
    if (args.has("scenes")) {
        std::stringstream list(args.get("scenes"));
        for (std::string item; std::getline(list, item, ',');)
            if (!item.empty()) scenes.push_back(item);
        if (scenes.empty()) throw UsageError("--scenes: expected a comma-separated list of scenes");
        return scenes;
    }
    scenes = {"cornell", "plane"};
    const std::vector<std::string> models = gltfModelsUnder(args.get("scenes-dir"));
    if (models.empty())
        std::printf("note: no glTF models under '%s' (--scenes-dir): built-in scenes only\n",
                    args.get("scenes-dir").c_str());
    scenes.insert(scenes.end(), models.begin(), models.end());
    return scenes;
}

// A short name for the table: the file's stem, or the built-in name.
std::string shortName(const std::string& scene) {
    return std::filesystem::path(scene).stem().string();
}

}  // namespace

int runScenesBenchmark(const ParsedArgs& args, const SessionOptions& session, const BenchmarkFrames& timing,
                       const std::filesystem::path& outDir) {
    const std::vector<std::string> names = sceneList(args);
    std::vector<Scene> scenes;
    scenes.reserve(names.size());
    for (const std::string& name : names)
        scenes.push_back(loadScene(name));  // a bad file fails before any frame

    nlohmann::json report;
    std::string table;
    {
        vk::Context context(session.context);
        std::printf("device: %s\n", context.deviceName().c_str());
        std::vector<BenchmarkRun> runs;
        for (size_t i = 0; i < scenes.size(); ++i) {
            runs.push_back({shortName(names[i]), &scenes[i], session.settings, nullptr, ""});
            runs.back().renderer = std::make_unique<Renderer>(context, scenes[i], session.settings);
        }
        printAnisotropy(session.settings.anisotropy, runs.front().renderer->settings().anisotropy);
        renderInterleaved(runs, timing.frames, timing.warmup, timing.block);

        const double cornellMs = [&] {
            for (const BenchmarkRun& run : runs)
                if (run.name == "cornell") return run.renderer->timer().frameStats().medianMs;
            return 0.0;
        }();
        report = {{"device", context.deviceName()},    {"width", session.settings.width},
                  {"height", session.settings.height}, {"frames", timing.frames},
                  {"warmup", timing.warmup},           {"block", timing.block},
                  {"scenes", nlohmann::json::array()}};
        // Columns: the passes of the first run that has them all (GI on: every pass).
        std::vector<std::string> passes;
        for (const vk::PassTiming& pass : runs.front().renderer->timer().passStats())
            passes.push_back(pass.name);
        table = passTableHeader("scene|frame ms|fps|÷ cornell", passes);
        for (size_t i = 0; i < runs.size(); ++i) {
            const Renderer& r = *runs[i].renderer;
            const double frameMs = r.timer().frameStats().medianMs;
            const double ratio = cornellMs > 0.0 ? frameMs / cornellMs : 0.0;
            nlohmann::json entry = timingJson(r);
            entry["name"] = runs[i].name;
            entry["scene"] = names[i];
            entry["over_cornell"] = ratio;
            report["scenes"].push_back(entry);
            char cells[128];
            std::snprintf(cells, sizeof(cells), "| %s | %.2f | %.1f | %.2f |", runs[i].name.c_str(), frameMs,
                          frameMs > 0.0 ? 1000.0 / frameMs : 0.0, ratio);
            table += cells + passTableCells(r, passes);
        }
    }
    checkValidation(session);
    char caption[300];
    std::snprintf(
        caption, sizeof(caption),
        "Device: %s, %ux%u, default configuration, %u frames in blocks of %u (medians after %u warm-up "
        "frames, ms).",
        report["device"].get<std::string>().c_str(), session.settings.width, session.settings.height,
        timing.frames, timing.block, timing.warmup);
    writeBenchmarkReport(outDir, "scenes", report, caption, table);
    return 0;
}

}  // namespace vct
