// vct benchmark: speed against error of the upsampling configurations (DESIGN §5), all in one run.
//
// One Vulkan device, one scene, one renderer per configuration: the reference (every pixel traced every
// frame, trace scale 1) and the low-res configurations (bilinear / normal / SG weights, with and without
// adaptive re-tracing). Frames are interleaved, config after config for each frame time, so every
// configuration sees the same machine load (what makes ratios between them meaningful on a shared CPU device).
// After the last frame each configuration's diffuse, specular and final images are compared with the
// reference's (linear HDR). Writes DIR/benchmark.json and DIR/benchmark.md and prints the table.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/cli.h"
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "io/image_metrics.h"
#include "scene/builtin_scenes.h"

namespace vct {

namespace {

struct Config {
    std::string name;
    RenderSettings settings;
    std::unique_ptr<Renderer> renderer;
};

// The configurations of one benchmark: the reference, then each guide without and with adaptive re-tracing.
std::vector<Config> makeConfigs(const RenderSettings& base, uint32_t scale) {
    std::vector<Config> configs;
    auto add = [&](const std::string& name, auto change) {
        Config config{name, base, nullptr};
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

double passMedian(const Renderer& renderer, const std::string& pass) {
    for (const vk::PassTiming& timing : renderer.timer().passStats())
        if (timing.name == pass) return timing.medianMs;
    return 0.0;
}

ImageRgba32f readImage(Renderer& renderer, vk::Image& image) {
    return {image.width(), image.height(), renderer.readFloatImage(image)};
}

}  // namespace

int runBenchmarkCommand(int argc, char** argv, int first) {
    std::vector<Option> options = {
        {"scene", "NAME|FILE", "built-in scene name or a .gltf/.glb file", "cornell"},
        {"size", "WxH", "image size in pixels", "320x180"},
        {"frames", "N", "frames per configuration (>= warmup + 30)", "64"},
        {"warmup", "K", "frames left out of the timing statistics", "10"},
        {"trace-scale", "2|4", "trace scale of the upsampled configurations", "4"},
        {"out", "DIR", "where benchmark.json and benchmark.md go", "out/benchmark"},
        {"device", "SUBSTRING", "use the first Vulkan device whose name contains SUBSTRING", ""},
        {"validate", "", "enable the Khronos validation layer; any message fails the run", ""},
        {"voxels", "N", "voxel grid resolution (default from the device)", ""},
        {"exposure", "X", "linear exposure before tone mapping", "1"}};
    for (Option& option : materialFilterOptions()) options.push_back(std::move(option));
    static const CommandSpec spec(
        "benchmark",
        "Times and measures the error of the upsampling configurations against trace scale 1, in one run.",
        options);
    auto parsed = spec.parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& args = *parsed;
    SessionOptions session = sessionOptions(args);
    const uint32_t frames = args.getUint("frames", 2, 100000);
    const uint32_t warmup = args.getUint("warmup", 0, frames - 1);
    const std::string scaleText = args.get("trace-scale");
    if (scaleText != "2" && scaleText != "4") throw UsageError("--trace-scale '" + scaleText + "': expected 2 or 4");
    const uint32_t scale = uint32_t(std::stoul(scaleText));
    const std::filesystem::path outDir = args.get("out");

    nlohmann::json report;
    std::string table;
    {
        const Scene scene = loadScene(session.scene);
        vk::Context context(session.context);
        std::printf("device: %s\n", context.deviceName().c_str());
        std::vector<Config> configs = makeConfigs(session.settings, scale);
        for (Config& config : configs) config.renderer = std::make_unique<Renderer>(context, scene, config.settings);
        printAnisotropy(session.settings.anisotropy, configs.front().renderer->settings().anisotropy);

        for (uint32_t frame = 0; frame < frames; ++frame) {
            const FrameInput input = fixedStepFrame(scene, frame, warmup);
            for (Config& config : configs) config.renderer->render(input);
        }

        Renderer& reference = *configs.front().renderer;
        const uint32_t w = session.settings.width, h = session.settings.height;
        const Renderer::IndirectLight refLight = reference.readIndirect();
        const ImageRgba32f refDiffuse{w, h, refLight.diffuse};
        const ImageRgba32f refSpecular{w, h, refLight.specular};
        const ImageRgba32f refFinal = readImage(reference, reference.targets().hdr);

        report = {{"device", context.deviceName()}, {"scene", session.scene}, {"width", w}, {"height", h},
                  {"frames", frames}, {"warmup", warmup}, {"trace_scale", scale}, {"configs", nlohmann::json::array()}};
        char line[400];
        std::snprintf(line, sizeof(line), "| %-20s | %8s | %8s | %8s | %8s | %8s | %10s | %10s | %10s | %8s |\n",
                      "configuration", "trace", "upsample", "resample", "frame", "re-traced", "MSE diff.",
                      "MSE spec.", "MSE final", "PSNR fin");
        table += line;
        table += "|" + std::string(22, '-') + "|" + std::string(10, '-') + "|" + std::string(10, '-') + "|" +
                 std::string(10, '-') + "|" + std::string(10, '-') + "|" + std::string(10, '-') + "|" +
                 std::string(12, '-') + "|" + std::string(12, '-') + "|" + std::string(12, '-') + "|" +
                 std::string(10, '-') + "|\n";
        for (Config& config : configs) {
            Renderer& r = *config.renderer;
            FrameTargets& t = r.targets();
            Renderer::IndirectLight light = r.readIndirect();
            const ImageError diffuse = compareImages(refDiffuse, {w, h, std::move(light.diffuse)});
            const ImageError specular = compareImages(refSpecular, {w, h, std::move(light.specular)});
            const ImageError final = compareImages(refFinal, readImage(r, t.hdr));
            nlohmann::json passes = nlohmann::json::object();
            for (const vk::PassTiming& timing : r.timer().passStats()) passes[timing.name] = timing.medianMs;
            const double frameMs = r.timer().frameStats().medianMs;
            auto errorJson = [](const ImageError& e) {
                return nlohmann::json{{"mse", e.mse}, {"rel_mse", e.relMse}, {"psnr", e.psnr}, {"max", e.maxAbs},
                                      {"non_finite", e.nonFinite}};
            };
            report["configs"].push_back({{"name", config.name},
                                         {"trace_scale", config.settings.traceScale},
                                         {"anisotropy", r.settings().anisotropy},
                                         {"pass_median_ms", passes},
                                         {"frame_median_ms", frameMs},
                                         {"resampled_fraction", r.resampledFraction()},
                                         {"error", {{"diffuse", errorJson(diffuse)},
                                                    {"specular", errorJson(specular)},
                                                    {"final", errorJson(final)}}}});
            std::snprintf(line, sizeof(line),
                          "| %-20s | %8.3f | %8.3f | %8.3f | %8.3f | %7.2f%% | %10.4g | %10.4g | %10.4g | %8.2f |\n",
                          config.name.c_str(), passMedian(r, "trace"), passMedian(r, "upsample"),
                          passMedian(r, "resample"), frameMs, 100.0 * r.resampledFraction(), diffuse.mse,
                          specular.mse, final.mse, final.psnr);
            table += line;
        }
        // The acceptance ratio: sg's upsample against normal's, both without re-tracing, same run.
        const double normalUpsample = passMedian(*configs[2].renderer, "upsample");
        const double sgUpsample = passMedian(*configs[3].renderer, "upsample");
        report["upsample_ratio_sg_over_normal"] = normalUpsample > 0.0 ? sgUpsample / normalUpsample : 0.0;
        std::snprintf(line, sizeof(line), "\nupsample sg / normal (medians, same run): %.3f\n",
                      normalUpsample > 0.0 ? sgUpsample / normalUpsample : 0.0);
        table += line;
    }
    checkValidation(session);

    std::error_code error;
    std::filesystem::create_directories(outDir, error);
    if (error) throw Error("cannot create output directory '" + outDir.string() + "': " + error.message());
    std::ofstream(outDir / "benchmark.json") << report.dump(2) << "\n";
    std::ofstream md(outDir / "benchmark.md");
    md << "Device: " << report["device"].get<std::string>() << ", scene " << session.scene << ", "
       << session.settings.width << "x" << session.settings.height << ", " << frames << " frames (medians after "
       << warmup << " warm-up frames, ms), trace scale " << scale
       << "; errors of the last frame against the reference, linear HDR.\n\n"
       << table;
    std::printf("%s", table.c_str());
    std::printf("wrote %s, %s\n", (outDir / "benchmark.json").c_str(), (outDir / "benchmark.md").c_str());
    return 0;
}

}  // namespace vct
