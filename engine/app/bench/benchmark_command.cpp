// vct benchmark: GPU-timed measurements in one run on one device (docs/design.md §8), in three modes.
//
// upsampling (default): speed against error of the upsampling configurations. One scene, one renderer per
//   configuration: the reference (every pixel traced every frame, trace scale 1) and the low-res
//   configurations (bilinear / normal / SG weights, with and without adaptive re-tracing). After the last
//   frame each configuration's diffuse, specular and final images are compared with the reference's (linear
//   HDR). Writes DIR/benchmark.json and DIR/benchmark.md.
// scenes: the default configuration on several scenes (app/bench/benchmark_scenes.cpp).
// scaling: per-pass cost against pixel count and voxel resolution (app/bench/benchmark_scaling.cpp).
// In every mode the renderers take turns in blocks of frames (app/bench/benchmark_run.h), so all of them see the
// same machine load, which is what makes ratios between them meaningful on a shared CPU device.
#include "app/bench/benchmark_command.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "app/bench/benchmark_modes.h"
#include "app/bench/benchmark_run.h"
#include "app/cli/cli.h"
#include "app/cli/session.h"
#include "core/error.h"
#include "io/safe_write.h"
#include "report/image_metrics.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_path.h"

namespace vct {

namespace {

// The configurations of one benchmark: the reference, then each guide without and with adaptive re-tracing.
std::vector<BenchmarkRun> makeConfigs(const Scene& scene, const RenderSettings& base, uint32_t scale) {
    std::vector<BenchmarkRun> configs;
    auto add = [&](const std::string& name, auto change) {
        BenchmarkRun config{name, &scene, base, nullptr, ""};
        change(config.settings);
        configs.push_back(std::move(config));
    };
    add("reference (scale 1)", [](RenderSettings& s) { s.traceScale = 1; });
    using W = RenderSettings::Weights;
    for (auto [weights, label] : {std::pair{W::Bilinear, "bilinear"}, {W::Normal, "normal"}, {W::Sg, "sg"}}) {
        add(std::string(label), [&](RenderSettings& s) {
            s.traceScale = scale;
            s.weights = weights;
            s.adaptive = false;
        });
    }
    for (auto [weights, label] : {std::pair{W::Normal, "normal+adaptive"}, {W::Sg, "sg+adaptive"}}) {
        add(std::string(label), [&](RenderSettings& s) {
            s.traceScale = scale;
            s.weights = weights;
            s.adaptive = true;
        });
    }
    return configs;
}

// Build: the configurations (makeConfigs), each with its renderer.
std::vector<BenchmarkRun> buildUpsamplingRuns(vk::Context& context, const Scene& scene,
                                              const RenderSettings& settings, uint32_t scale) {
    std::vector<BenchmarkRun> configs = makeConfigs(scene, settings, scale);
    for (BenchmarkRun& config : configs)
        config.renderer = std::make_unique<Renderer>(context, scene, config.settings);
    printAnisotropy(settings.anisotropy, configs.front().renderer->settings().anisotropy);
    return configs;
}

// Run: every configuration renders the same frames, interleaved in blocks, along --camera-path if given.
void runUpsampling(std::vector<BenchmarkRun>& configs, const ParsedArgs& args,
                   const BenchmarkFrames& timing) {
    const std::optional<CameraPath> path =
        args.has("camera-path") ? std::optional<CameraPath>(loadCameraPath(args.get("camera-path")))
                                : std::nullopt;
    FrameHooks hooks;
    if (path)
        hooks.frameInput = [&](const BenchmarkRun& run, uint32_t frame, uint32_t warmup) {
            return fixedStepFrame(*run.scene, frame, warmup, &*path);
        };
    renderInterleaved(configs, timing.frames, timing.warmup, timing.block, hooks);
}

// Report: each configuration's pass medians and its errors against the reference (the first) into
// report["configs"] and a table row, then the acceptance ratios.
void reportUpsampling(std::vector<BenchmarkRun>& configs, uint32_t w, uint32_t h, nlohmann::json& report,
                      std::string& table) {
    Renderer& reference = *configs.front().renderer;
    const Renderer::IndirectLight refLight = reference.readIndirect();
    const ImageRgba32f refDiffuse{w, h, refLight.diffuse};
    const ImageRgba32f refSpecular{w, h, refLight.specular};
    const ImageRgba32f refFinal{w, h, reference.readFinalHdr()};
    // The indirect light's cost: what tracing fewer pixels is meant to save (trace + upsample +
    // re-trace).
    auto indirectMs = [](const Renderer& r) {
        return passMedian(r, "trace") + passMedian(r, "upsample") + passMedian(r, "resample");
    };
    const double referenceIndirect = indirectMs(reference);
    char line[512];
    std::snprintf(line, sizeof(line),
                  "| %-20s | %8s | %8s | %8s | %8s | %8s | %8s | %8s | %8s | %10s | %10s | %10s | %8s |\n",
                  "configuration", "trace", "upsample", "resample", "indirect", "ind/ref", "ups/trc", "frame",
                  "re-traced", "MSE diff.", "MSE spec.", "MSE final", "PSNR fin");
    table += line;
    table += "|" + std::string(22, '-');
    for (int column = 0; column < 8; ++column) table += "|" + std::string(10, '-');
    for (int column = 0; column < 3; ++column) table += "|" + std::string(12, '-');
    table += "|" + std::string(10, '-') + "|\n";
    for (BenchmarkRun& config : configs) {
        Renderer& r = *config.renderer;
        Renderer::IndirectLight light = r.readIndirect();
        const ImageError diffuse = compareImages(refDiffuse, {w, h, std::move(light.diffuse)});
        const ImageError specular = compareImages(refSpecular, {w, h, std::move(light.specular)});
        const ImageError final = compareImages(refFinal, {w, h, r.readFinalHdr()});
        auto errorJson = [](const ImageError& e) {
            return nlohmann::json{{"mse", e.mse},
                                  {"rel_mse", e.relMse},
                                  {"psnr", e.psnr},
                                  {"max", e.maxAbs},
                                  {"non_finite", e.nonFinite}};
        };
        const double indirect = indirectMs(r), trace = passMedian(r, "trace");
        const double indirectRatio = referenceIndirect > 0.0 ? indirect / referenceIndirect : 0.0;
        const double upsampleRatio = trace > 0.0 ? passMedian(r, "upsample") / trace : 0.0;
        nlohmann::json entry = timingJson(r);
        entry["name"] = config.name;
        entry["trace_scale"] = config.settings.traceScale;
        entry["anisotropy"] = r.settings().anisotropy;
        entry["indirect_ms"] = indirect;
        entry["indirect_over_reference"] = indirectRatio;
        entry["upsample_over_trace"] = upsampleRatio;
        entry["resampled_fraction"] = r.resampledFraction();
        entry["error"] = {
            {"diffuse", errorJson(diffuse)}, {"specular", errorJson(specular)}, {"final", errorJson(final)}};
        report["configs"].push_back(entry);
        std::snprintf(line, sizeof(line),
                      "| %-20s | %8.3f | %8.3f | %8.3f | %8.3f | %8.3f | %8.3f | %8.3f | %7.2f%% | %10.4g | "
                      "%10.4g | %10.4g | %8.2f |\n",
                      config.name.c_str(), trace, passMedian(r, "upsample"), passMedian(r, "resample"),
                      indirect, indirectRatio, upsampleRatio, r.timer().frameStats().medianMs,
                      100.0 * r.resampledFraction(), diffuse.mse, specular.mse, final.mse, final.psnr);
        table += line;
    }
    // The acceptance ratios (issue 8), same run: sg's upsample against normal's (both without
    // re-tracing), and for the default configuration (sg + adaptive) upsample against trace, indirect
    // against reference.
    const double normalUpsample = passMedian(*configs[2].renderer, "upsample");
    const double sgUpsample = passMedian(*configs[3].renderer, "upsample");
    const nlohmann::json& method = report["configs"].back();
    report["upsample_ratio_sg_over_normal"] = normalUpsample > 0.0 ? sgUpsample / normalUpsample : 0.0;
    report["upsample_over_trace"] = method["upsample_over_trace"];
    report["indirect_over_reference"] = method["indirect_over_reference"];
    std::snprintf(line, sizeof(line),
                  "\nsg+adaptive: upsample / trace %.3f, indirect / reference indirect %.3f; upsample sg / "
                  "normal %.3f (medians, same run)\n",
                  method["upsample_over_trace"].get<double>(),
                  method["indirect_over_reference"].get<double>(),
                  normalUpsample > 0.0 ? sgUpsample / normalUpsample : 0.0);
    table += line;
}

// The upsampling mode: the reference and the five low-res configurations, errors against the reference.
int runUpsamplingBenchmark(const ParsedArgs& args, const SessionOptions& session,
                           const BenchmarkFrames& timing, const std::filesystem::path& outDir) {
    const std::string scaleText = args.get("trace-scale");
    if (scaleText != "2" && scaleText != "4")
        throw UsageError("--trace-scale '" + scaleText + "': expected 2 or 4");
    const uint32_t scale = uint32_t(std::stoul(scaleText));

    nlohmann::json report;
    std::string table;
    {
        const Scene scene = loadScene(session.scene);
        vk::Context context(session.context);
        std::printf("device: %s\n", context.deviceName().c_str());
        std::vector<BenchmarkRun> configs = buildUpsamplingRuns(context, scene, session.settings, scale);
        runUpsampling(configs, args, timing);
        const uint32_t w = session.settings.width, h = session.settings.height;
        report = {{"device", context.deviceName()},
                  {"scene", session.scene},
                  {"width", w},
                  {"height", h},
                  {"frames", timing.frames},
                  {"warmup", timing.warmup},
                  {"block", timing.block},
                  {"trace_scale", scale},
                  {"configs", nlohmann::json::array()}};
        reportUpsampling(configs, w, h, report, table);
    }
    checkValidation(session);
    char caption[300];
    std::snprintf(
        caption, sizeof(caption),
        "Device: %s, scene %s, %ux%u, %u frames in blocks of %u (medians after %u warm-up frames, ms), "
        "trace scale %u; indirect = trace + upsample + resample; errors of the last frame against the "
        "reference, linear HDR.",
        report["device"].get<std::string>().c_str(), session.scene.c_str(), session.settings.width,
        session.settings.height, timing.frames, timing.block, timing.warmup, scale);
    writeBenchmarkReport(outDir, "benchmark", report, caption, table);
    return 0;
}

// --size, smaller than render's by default.
Option benchmarkSize() {
    Option size = settingOption("size");
    size.help += " (scaling: the size of the voxel-resolution sweep)";
    size.defaultValue = "320x180";
    return size;
}

}  // namespace

int runBenchmarkCommand(int argc, char** argv, int first) {
    std::vector<Option> options = {
        {"mode", "upsampling|scenes|scaling|report|study",
         "upsampling: configurations against trace scale 1; scenes: the default configuration on several "
         "scenes; scaling: cost against pixel count and voxel resolution; report: speed against error on the "
         "report scenes, static, moving and cut cameras, errors every frame; study: Tokuyoshi 2015's Fig. 6 "
         "parameter "
         "study (beta x kappa, sigma_n, diffuse lobe) per material class",
         "upsampling"},
        {"report-scenes", "FILE.json", "report, study: the scene list (names, scenes, camera paths)",
         "scenes/report_scenes.json"},
        {"cameras", "LIST", "report: which cameras, of static, moving (the scene's camera path) and cut",
         "static,moving,cut"},
        {"camera-path", "FILE.json", "upsampling: play this camera path instead of the scene camera", ""},
        {"dump-last", "DIR",
         "report: write the static camera's last frame of every configuration (and of the reference) as "
         "DIR/SCENE/CONFIG/{final,direct,diffuse_indirect,specular_indirect}.exr for vct compare "
         "--reference-dir, and DIR/manifest.json",
         ""},
        {"scene", "NAME|FILE", "built-in scene name or a .gltf/.glb file (upsampling, scaling)", "cornell"},
        {"scenes", "A,B,...",
         "scenes mode: built-in names and glTF files (default: cornell, plane and every "
         "glTF under --scenes-dir)",
         ""},
        {"scenes-dir", "DIR", "scenes mode: where to look for glTF models (DIR/*/glTF/*.gltf, DIR/*/*.glb)",
         "../shared/scenes"},
        benchmarkSize(),
        {"frames", "N", "frames per configuration (>= warmup + 30 for claims)", "64"},
        {"warmup", "K", "frames left out of the timing statistics (default: min(10, frames/4))", ""},
        {"block", "B", "frames a configuration renders in a row before the next takes its turn", "8"},
        {"trace-scale", "2|4", "upsampling: trace scale of the upsampled configurations", "4"},
        {"out", "DIR", "where the report (.json, .md) goes", "out/benchmark"},
        {"device", "SUBSTRING", "use the first Vulkan device whose name contains SUBSTRING", ""},
        {"validate", "", "enable the Khronos validation layer; any message fails the run", ""},
        settingOption("voxels"),
        settingOption("bounces"),
        settingOption("exposure"),
        settingOption("recompute-every-frame"),
        // The per-device layouts, to time one against the other on one device.
        settingOption("trace-layout"),
        settingOption("upsample-layout")};
    for (Option& option : settingOptions(SettingGroup::Material)) options.push_back(std::move(option));
    static const CommandSpec spec("benchmark", "GPU-timed measurements in one run: see --mode.", options);
    auto parsed = spec.parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& args = *parsed;
    SessionOptions session = sessionOptions(args);
    const std::string mode = args.get("mode");
    // The modes that measure the upsampling's error against the every-pixel trace (upsampling, report, study)
    // run the fixed cone set: with turned cones trace scale 1 keeps a history and is no longer the fresh trace
    // of the frame, and the low-res configurations' turn noise would count as the upsampling's error
    // (docs/design.md §5.5, §8.3). scenes and scaling time the default configuration.
    if (mode == "upsampling" || mode == "report" || mode == "study") session.settings.coneRotation = false;
    BenchmarkFrames timing;
    timing.frames = args.getUint("frames", 2, 100000);
    timing.warmup =
        args.has("warmup") ? args.getUint("warmup", 0, timing.frames - 1) : std::min(10u, timing.frames / 4);
    timing.block = args.getUint("block", 1, 100000);
    if (args.has("dump-last") && mode != "report") throw UsageError("--dump-last: only with --mode report");
    const std::filesystem::path outDir = args.get("out");
    prepareOutputDirectory(outDir, "--out");  // before any frame: not only once the report is written
    if (mode == "upsampling") return runUpsamplingBenchmark(args, session, timing, outDir);
    if (mode == "scenes") return runScenesBenchmark(args, session, timing, outDir);
    if (mode == "scaling") return runScalingBenchmark(args, session, timing, outDir);
    if (mode == "report") return runReportBenchmark(args, session, timing, outDir);
    if (mode == "study") return runStudyBenchmark(args, session, timing, outDir);
    throw UsageError("--mode '" + mode + "': expected upsampling, scenes, scaling, report or study");
}

}  // namespace vct
