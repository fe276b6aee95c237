// vct benchmark --mode report: speed against error as one report (docs/design.md §8.4, issue 9). For every
// scene of the report list (scenes/report_scenes.json) and every camera (static; the scene's camera path; a
// cut halfway), one run renders, interleaved on one device:
//   - the reference: every pixel traced every frame (trace scale 1);
//   - trace scales 2 and 4 × weights bilinear / normal / sg × adaptive re-tracing off / on;
//   - on the moving camera, sg + adaptive at scale 4 with τ swept (re-traced fraction and error against τ).
// After every frame each configuration's demodulated diffuse and specular light and its final image are
// compared with the reference's same frame: PSNR on the indirect buffers (peak = the reference's largest
// value), on the tone-mapped sRGB final (peak 1), MSE and relative MSE on linear HDR. Per-pass GPU medians
// come from the same run. Writes DIR/report.json (plots: benchmarks/plot_report.py) and DIR/report.md.
// --dump-last DUMP also writes, for the static camera, every configuration's last frame (the reference's
// included) as DUMP/SCENE/CONFIG/{final,direct,diffuse_indirect,specular_indirect}.exr, what
// `vct compare --reference-dir` measures against a path-traced reference of that frame (`vct reference
// --frame FRAMES-1`; benchmarks/report.sh), and DUMP/manifest.json listing them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "app/bench/benchmark_modes.h"
#include "app/bench/benchmark_run.h"
#include "app/cli/aux_output.h"
#include "core/error.h"
#include "io/safe_write.h"
#include "report/image_metrics.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_path.h"
#include "scene/input_limits.h"

namespace vct {

namespace {

using nlohmann::json;

// One frame's images of a renderer: what the errors are measured on (display: the tone-mapped sRGB final,
// made once per frame, not once per comparison).
struct FrameImages {
    ImageRgba32f diffuse, specular, hdr, display;
};

FrameImages readFrame(Renderer& renderer) {
    const uint32_t w = renderer.settings().width, h = renderer.settings().height;
    Renderer::IndirectLight light = renderer.readIndirect();
    ImageRgba32f hdr{w, h, renderer.readFinalHdr()};
    ImageRgba32f display = toneMappedSrgb(hdr, renderer.settings().exposure);
    return {{w, h, std::move(light.diffuse)},
            {w, h, std::move(light.specular)},
            std::move(hdr),
            std::move(display)};
}

json errorJson(const ImageError& e) {
    return {{"mse", e.mse}, {"rel_mse", e.relMse}, {"psnr", e.psnr}, {"non_finite", e.nonFinite}};
}

// A JSON number for a PSNR that may be infinite (identical images): JSON has no Inf, so a large finite value.
double finitePsnr(double psnr) {
    return std::isfinite(psnr) ? psnr : 200.0;
}

// A name as a directory name: runs of anything but letters and digits become one '-' ("s4 sg+adaptive" →
// "s4-sg-adaptive").
std::string pathSlug(const std::string& name) {
    std::string slug;
    for (char c : name) {
        const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        if (keep)
            slug += c;
        else if (!slug.empty() && slug.back() != '-')
            slug += '-';
    }
    while (!slug.empty() && slug.back() == '-') slug.pop_back();
    return slug.empty() ? "unnamed" : slug;
}

// The report's scenes: --scenes (comma-separated built-in names or files) or the list file. Entries whose
// file is missing (the shared glTF models on a machine without them) are skipped with a note.
}  // namespace

std::vector<ReportScene> reportScenes(const ParsedArgs& args) {
    const std::filesystem::path listFile = args.get("report-scenes");
    const std::filesystem::path listDir = listFile.parent_path();
    // The one checked open: a FIFO is refused instead of blocking.
    const FileRead read = readRegularFile(listFile, uint64_t(1) << 24);
    if (!read.error.empty()) throw Error("report scene list '" + listFile.string() + "': " + read.error);
    const std::string_view text(reinterpret_cast<const char*>(read.bytes.data()), read.bytes.size());
    if (jsonNestingDepth(text, kMaxJsonDepth) > kMaxJsonDepth)
        throw Error("report scene list '" + listFile.string() + "': JSON nested too deep");
    json list;
    try {
        list = json::parse(text);
    } catch (const json::exception& e) {
        throw Error("report scene list '" + listFile.string() + "': not valid JSON (" + e.what() + ")");
    }
    if (!list.is_object() || !list.contains("scenes") || !list["scenes"].is_array())
        throw Error("report scene list '" + listFile.string() + "': needs a \"scenes\" array");
    std::vector<std::string> only;
    if (args.has("scenes")) {
        std::stringstream names(args.get("scenes"));
        for (std::string item; std::getline(names, item, ',');)
            if (!item.empty()) only.push_back(item);
    }
    std::vector<ReportScene> scenes;
    for (const json& entry : list["scenes"]) {
        if (!entry.is_object() || !entry.contains("name") || !entry.contains("scene"))
            throw Error("report scene list '" + listFile.string() +
                        "': every entry needs \"name\" and \"scene\"");
        ReportScene scene{entry["name"].get<std::string>(), entry["scene"].get<std::string>(), std::nullopt};
        if (!only.empty() && std::find(only.begin(), only.end(), scene.name) == only.end()) continue;
        if (entry.value("shared", false)) {
            const std::filesystem::path file = std::filesystem::path(args.get("scenes-dir")) / scene.scene;
            std::error_code error;
            if (!std::filesystem::is_regular_file(file, error)) {
                std::printf("note: %s skipped: '%s' not found (--scenes-dir)\n", scene.name.c_str(),
                            file.c_str());
                continue;
            }
            scene.scene = file.string();
        }
        if (entry.contains("camera_path"))
            scene.path = loadCameraPath(listDir / entry["camera_path"].get<std::string>());
        scenes.push_back(std::move(scene));
    }
    if (scenes.empty()) throw UsageError("report: no scene to measure (--scenes, --report-scenes)");
    return scenes;
}

namespace {

// The configurations of one (scene, camera) run.
std::vector<BenchmarkRun> reportConfigs(const Scene& scene, const RenderSettings& base, bool tauSweep) {
    std::vector<BenchmarkRun> configs;
    auto add = [&](const std::string& name, auto change) {
        BenchmarkRun config{name, &scene, base, nullptr, ""};
        change(config.settings);
        configs.push_back(std::move(config));
    };
    add("reference", [](RenderSettings& s) { s.traceScale = 1; });
    using W = RenderSettings::Weights;
    for (uint32_t scale : {2u, 4u})
        for (W weights : {W::Bilinear, W::Normal, W::Sg})
            for (bool adaptive : {false, true})
                add("s" + std::to_string(scale) + " " + weightsName(weights) + (adaptive ? "+adaptive" : ""),
                    [&](RenderSettings& s) {
                        s.traceScale = scale;
                        s.weights = weights;
                        s.adaptive = adaptive;
                    });
    if (tauSweep)
        for (float tau : {0.05f, 0.1f, 0.5f, 1.0f, 2.0f, 4.0f}) {
            char name[64];
            std::snprintf(name, sizeof(name), "s4 sg+adaptive tau %g", tau);
            add(name, [&](RenderSettings& s) {
                s.traceScale = 4;
                s.weights = W::Sg;
                s.adaptive = true;
                s.tau = tau;
            });
        }
    return configs;
}

struct ReportCamera {
    std::string name;  // static, moving, cut
    const CameraPath* path = nullptr;
    uint32_t cutFrame = 0;  // 0: none
};

// A configuration's errors against the reference, one value per frame.
struct ErrorCurves {
    std::vector<double> diffuse, specular, finalSrgb, retraced;
};

double indirectMs(const Renderer& r) {
    return passMedian(r, "trace") + passMedian(r, "upsample") + passMedian(r, "resample");
}

// The reference configuration's (trace scale 1) costs, which the others are divided by.
struct ReferenceCosts {
    double indirectMs = 0.0;
    double frameMs = 0.0;
};

// One configuration's JSON: timings, costs over the reference's and, but for the reference itself (`error`
// null), the last frame's errors and the per-frame curves.
json configJson(const BenchmarkRun& config, const ReferenceCosts& reference, const json* error,
                const ErrorCurves& c) {
    const Renderer& r = *config.renderer;
    json entryJson = timingJson(r);
    entryJson["name"] = config.name;
    entryJson["indirect_ms"] = indirectMs(r);
    entryJson["indirect_over_reference"] =
        reference.indirectMs > 0.0 ? indirectMs(r) / reference.indirectMs : 0.0;
    entryJson["frame_over_reference"] =
        reference.frameMs > 0.0 ? r.timer().frameStats().medianMs / reference.frameMs : 0.0;
    if (error) {
        entryJson["error"] = *error;
        double meanRetraced = 0.0;
        for (double f : c.retraced) meanRetraced += f / double(std::max<size_t>(c.retraced.size(), 1));
        entryJson["resampled_fraction"] = c.retraced.empty() ? 0.0 : c.retraced.back();
        entryJson["resampled_fraction_mean"] = meanRetraced;
        entryJson["curves"] = {{"diffuse_psnr", c.diffuse},
                               {"specular_psnr", c.specular},
                               {"final_srgb_psnr", c.finalSrgb},
                               {"resampled_fraction", c.retraced}};
    }
    entryJson["settings"]["tau_used"] = resampleThreshold(r.settings());
    return entryJson;
}

// The configuration's row of the Markdown table, from its JSON.
std::string tableRow(const ReportScene& entry, const ReportCamera& camera, const BenchmarkRun& config,
                     const json& entryJson) {
    const Renderer& r = *config.renderer;
    char line[512];
    if (entryJson.contains("error")) {
        const json& error = entryJson["error"];
        auto psnrOf = [&](const char* buffer) { return finitePsnr(error[buffer]["psnr"].get<double>()); };
        std::snprintf(
            line, sizeof(line),
            "| %s | %s | %s | %.2f | %.2f | %.2f | %.3f | %.2f | %.2f | %.2f | %.3g | %.3g | %.2f%% |\n",
            entry.name.c_str(), camera.name.c_str(), config.name.c_str(), r.timer().frameStats().medianMs,
            passMedian(r, "upsample"), indirectMs(r), entryJson["indirect_over_reference"].get<double>(),
            psnrOf("diffuse"), psnrOf("specular"), psnrOf("final_srgb"),
            error["final_hdr"]["mse"].get<double>(), error["final_hdr"]["rel_mse"].get<double>(),
            100.0 * entryJson["resampled_fraction_mean"].get<double>());
    } else {
        std::snprintf(line, sizeof(line), "| %s | %s | %s | %.2f | – | %.2f | 1 | – | – | – | – | – | – |\n",
                      entry.name.c_str(), camera.name.c_str(), config.name.c_str(),
                      r.timer().frameStats().medianMs, indirectMs(r));
    }
    return line;
}

// One (scene, camera) run: configurations interleaved, errors every frame. Returns its JSON and adds its rows
// to the Markdown table. With `dumpDir`, writes each configuration's last frame into dumpDir/CONFIG/ and
// lists them in the JSON's "last_frame".
json measureCamera(vk::Context& context, const Scene& scene, const ReportScene& entry,
                   const ReportCamera& camera, const SessionOptions& session, const BenchmarkFrames& timing,
                   std::string& table, const std::filesystem::path* dumpDir) {
    std::vector<BenchmarkRun> configs = reportConfigs(scene, session.settings, camera.name == "moving");
    for (BenchmarkRun& config : configs)
        config.renderer = std::make_unique<Renderer>(context, scene, config.settings);
    // The reference's frames of the current block, kept until every configuration has rendered them.
    std::map<uint32_t, FrameImages> referenceFrames;
    std::vector<ErrorCurves> curves(configs.size());
    std::vector<json> lastErrors(configs.size());  // every metric of the last frame
    FrameHooks hooks;
    hooks.frameInput = [&](const BenchmarkRun& run, uint32_t frame, uint32_t warmup) {
        FrameInput input = fixedStepFrame(*run.scene, frame, warmup, camera.path);
        if (camera.cutFrame && frame == camera.cutFrame) input.cut = true;
        if (camera.cutFrame && frame >= camera.cutFrame) input.camera = cutCamera(input.camera);
        return input;
    };
    hooks.afterFrame = [&](size_t index, uint32_t frame) {
        Renderer& renderer = *configs[index].renderer;
        FrameImages images = readFrame(renderer);
        if (index == 0) {
            // Blocks run the reference first: drop the frames of the previous block.
            referenceFrames.erase(
                referenceFrames.begin(),
                referenceFrames.lower_bound(frame >= timing.block ? frame - timing.block : 0));
            referenceFrames[frame] = std::move(images);
            return;
        }
        const FrameImages& reference = referenceFrames.at(frame);
        const ImageError diffuse = compareImages(reference.diffuse, images.diffuse);
        const ImageError specular = compareImages(reference.specular, images.specular);
        const ImageError finalSrgb = compareImages(reference.display, images.display, 1.0);
        ErrorCurves& c = curves[index];
        c.diffuse.push_back(finitePsnr(diffuse.psnr));
        c.specular.push_back(finitePsnr(specular.psnr));
        c.finalSrgb.push_back(finitePsnr(finalSrgb.psnr));
        c.retraced.push_back(renderer.resampledFraction());
        if (frame + 1 == timing.frames)
            lastErrors[index] = {{"diffuse", errorJson(diffuse)},
                                 {"specular", errorJson(specular)},
                                 {"final_hdr", errorJson(compareImages(reference.hdr, images.hdr))},
                                 {"final_srgb", errorJson(finalSrgb)}};
    };
    std::fprintf(stderr, "report: %s, %s camera, %zu configurations\n", entry.name.c_str(),
                 camera.name.c_str(), configs.size());
    renderInterleaved(configs, timing.frames, timing.warmup, std::max(timing.block, 1u), hooks);

    // The last frames, read back once every configuration has rendered all of its frames (outside the
    // timings): each renderer still holds its last frame.
    std::vector<std::string> dumpSlugs(configs.size());
    if (dumpDir) {
        for (size_t index = 0; index < configs.size(); ++index) {
            dumpSlugs[index] = pathSlug(configs[index].name);
            const std::filesystem::path dir = *dumpDir / dumpSlugs[index];
            prepareOutputDirectory(dir, "--dump-last");
            writeLightImages(*configs[index].renderer, dir);
        }
        std::printf("wrote the last frames (%u) of %s, %s camera, into %s\n", timing.frames - 1,
                    entry.name.c_str(), camera.name.c_str(), dumpDir->c_str());
    }

    const Renderer& reference = *configs[0].renderer;
    const ReferenceCosts referenceCosts{indirectMs(reference), reference.timer().frameStats().medianMs};
    json out = {{"scene", entry.name}, {"camera", camera.name}, {"configs", json::array()}};
    if (camera.cutFrame) out["cut_frame"] = camera.cutFrame;
    if (dumpDir) out["last_frame"] = {{"frame", timing.frames - 1}, {"dir", dumpDir->string()}};
    for (size_t index = 0; index < configs.size(); ++index) {
        json entryJson = configJson(configs[index], referenceCosts, index > 0 ? &lastErrors[index] : nullptr,
                                    curves[index]);
        table += tableRow(entry, camera, configs[index], entryJson);
        if (dumpDir) entryJson["last_frame_dir"] = dumpSlugs[index];
        out["configs"].push_back(entryJson);
    }
    return out;
}

std::vector<std::string> reportCameras(const ParsedArgs& args) {
    std::vector<std::string> cameras;
    std::stringstream list(args.get("cameras"));
    for (std::string item; std::getline(list, item, ',');) {
        if (item != "static" && item != "moving" && item != "cut")
            throw UsageError("--cameras '" + item + "': expected static, moving and/or cut");
        cameras.push_back(item);
    }
    return cameras;
}

// A scene's entry in the dump's manifest: what `vct reference` needs to render the same frame, and the
// configurations' directories.
json manifestEntry(const ReportScene& entry, const json& run) {
    // A glTF file by its absolute path (benchmarks/report.sh may run vct reference elsewhere); a built-in
    // scene by its name.
    std::string sceneSpec = entry.scene;
    const std::vector<std::string> builtins = builtinSceneNames();
    if (std::find(builtins.begin(), builtins.end(), entry.scene) == builtins.end())
        sceneSpec = std::filesystem::absolute(entry.scene).lexically_normal().string();
    json configs = json::array();
    for (const json& config : run["configs"])
        configs.push_back({{"name", config["name"]},
                           {"dir", config["last_frame_dir"]},
                           {"trace_scale", config["settings"]["trace_scale"]},
                           {"frame_median_ms", config["frame_median_ms"]}});
    return {{"name", entry.name},
            {"scene", sceneSpec},
            {"dir", pathSlug(entry.name)},
            {"camera_path", nullptr},
            {"configs", configs}};
}

}  // namespace

int runReportBenchmark(const ParsedArgs& args, const SessionOptions& session, const BenchmarkFrames& timing,
                       const std::filesystem::path& outDir) {
    if (timing.block > 8)
        throw UsageError("--block: at most 8 in report mode (reference frames are kept per block)");
    const std::vector<ReportScene> scenes = reportScenes(args);
    const std::vector<std::string> cameras = reportCameras(args);
    // --dump-last: checked and made before any frame, as --out is.
    std::optional<std::filesystem::path> dumpDir;
    if (args.has("dump-last")) {
        dumpDir = std::filesystem::path(args.get("dump-last"));
        prepareOutputDirectory(*dumpDir, "--dump-last");
        if (std::find(cameras.begin(), cameras.end(), "static") == cameras.end())
            std::printf("note: --dump-last: no static camera in --cameras, no last frame written\n");
    }
    // The dump's manifest: per scene, what `vct reference` needs to render the same frame, and the
    // configurations' directories.
    json manifest = {{"frame", timing.frames - 1},
                     {"width", session.settings.width},
                     {"height", session.settings.height},
                     {"exposure", session.settings.exposure},
                     {"camera", "static"},
                     {"scenes", json::array()}};
    json report = {
        {"frames", timing.frames},         {"warmup", timing.warmup},           {"block", timing.block},
        {"width", session.settings.width}, {"height", session.settings.height}, {"runs", json::array()}};
    std::string table =
        "| scene | camera | configuration | frame ms | upsample ms | indirect ms | ind/ref | diffuse PSNR | "
        "specular "
        "PSNR | final sRGB PSNR | final MSE | final rel. MSE | re-traced (mean) |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    {
        vk::Context context(session.context);
        std::printf("device: %s\n", context.deviceName().c_str());
        report["device"] = context.deviceName();
        for (const ReportScene& entry : scenes) {
            const Scene scene = loadScene(entry.scene);
            for (const std::string& cameraName : cameras) {
                ReportCamera camera{cameraName, nullptr, 0};
                if (cameraName == "moving") {
                    if (!entry.path) {
                        std::printf("note: %s has no camera path: no moving camera\n", entry.name.c_str());
                        continue;
                    }
                    camera.path = &*entry.path;
                }
                if (cameraName == "cut") camera.cutFrame = timing.frames / 2;
                // Only the static camera's last frame is dumped: the frame `vct reference --frame` renders
                // with the scene's own camera.
                std::optional<std::filesystem::path> sceneDump;
                if (dumpDir && cameraName == "static") sceneDump = *dumpDir / pathSlug(entry.name);
                json run = measureCamera(context, scene, entry, camera, session, timing, table,
                                         sceneDump ? &*sceneDump : nullptr);
                if (sceneDump) manifest["scenes"].push_back(manifestEntry(entry, run));
                report["runs"].push_back(std::move(run));
            }
        }
    }
    checkValidation(session);
    if (dumpDir) {
        report["last_frame_dump"] = dumpDir->string();
        writeTextReplacing(*dumpDir / "manifest.json", manifest.dump(2) + "\n");
        std::printf("wrote %s\n", (*dumpDir / "manifest.json").c_str());
    }
    char caption[800];
    std::snprintf(
        caption, sizeof(caption),
        "Device: %s, %ux%u, %u frames per configuration in blocks of %u (GPU medians after %u warm-up "
        "frames, ms). Errors of the last frame against the reference of the same run (trace scale 1): "
        "PSNR of the demodulated indirect light (peak = reference max) and of the tone-mapped sRGB final "
        "(peak 1); MSE and relative MSE of the final on linear HDR. indirect = trace + upsample + "
        "resample. Plots: benchmarks/plot_report.py.",
        report["device"].get<std::string>().c_str(), session.settings.width, session.settings.height,
        timing.frames, timing.block, timing.warmup);
    writeBenchmarkReport(outDir, "report", report, caption, table);
    return 0;
}

}  // namespace vct
