// vct reference: the path-traced ground truth of one frame (engine/reference/path_tracer.h), written in vct's
// own units into a directory that `vct compare --reference-dir` reads.
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "app/cli/cli.h"
#include "app/cli/commands.h"
#include "app/cli/progress_line.h"
#include "app/cli/session.h"
#include "core/error.h"
#include "io/safe_write.h"
#include "reference/path_tracer.h"
#include "reference/reference_output.h"
#include "render/renderer.h"
#include "render/settings.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_path.h"

namespace vct {

namespace {

// Pixels × samples the command accepts: bounded so that a typo cannot ask for days of work (640×360 at 16384
// spp is 3.8·10⁹ samples).
constexpr uint64_t kMaxSamples = uint64_t(1) << 32;

const CommandSpec& referenceSpec() {
    static const CommandSpec spec(
        "reference",
        "Path-traces the ground truth of one frame on the CPU (Embree) and writes DIR/final.exr, direct.exr, "
        "diffuse_indirect.exr, specular_indirect.exr, indirect.exr (each with *_variance.exr), "
        "surface_id.exr, final.png "
        "and "
        "reference.json, in the units of vct render --aux.",
        {{"scene", "NAME|FILE", "built-in scene name (see vct scenes) or a .gltf/.glb file", "cornell"},
         {"size", "WxH", "image size in pixels (the pixel grid of vct render --size)", "320x180"},
         {"frame", "K",
          "render frame K of vct render: the scene at t = K/60 s, and --camera-path at that time", "0"},
         {"camera-path", "FILE.json",
          "the camera of this keyframed path (as vct render) instead of the scene's", ""},
         {"spp", "N",
          "samples per pixel (each: one camera ray, light samples, one diffuse and one specular ray)", "64"},
         {"seed", "S", "random seed: the image is the same for a seed, whatever the thread count", "1"},
         {"bounces", "0|1|N|all",
          "indirect bounces: 0 direct only, 1 what vct's cones estimate (vct --bounces 1), N, all (full GI, "
          "Russian roulette: what vct's default converges to)",
          "all"},
         {"secondary", "full|diffuse",
          "how surfaces hit by indirect rays reflect: the full BRDF (the truth) or its Lambert part only "
          "(what "
          "vct's voxels store)",
          "full"},
         {"threads", "N", "worker threads (0: every hardware thread)", "0"},
         {"exposure", "X", "linear exposure of final.png's tone map", "1"},
         {"out", "DIR", "output directory (created if missing)", "reference"},
         // The environment, as vct render makes it (render/environment.h: sceneEnvironment).
         settingOption("environment"),
         settingOption("environment-intensity"),
         settingOption("environment-rotation"),
         settingOption("sky-turbidity")});
    return spec;
}

int parseBounces(const std::string& text) {
    if (text == "all") return reference::kUnlimitedBounces;
    uint32_t value = 0;
    const char* end = text.data() + text.size();
    auto [ptr, error] = std::from_chars(text.data(), end, value);
    if (error != std::errc() || ptr != end || value > 64)
        throw UsageError("--bounces '" + text + "': expected 0 to 64 or all");
    return int(value);
}

// The progress line on a terminal only: when stderr is a file or pipe, logs stay one line per event.
class ProgressBar {
  public:
    explicit ProgressBar(bool enabled) : enabled_(enabled) {}
    void update(float fraction) {
        const int percent = int(fraction * 100.0f);
        if (!enabled_ || percent == last_) return;
        last_ = percent;
        printProgressLine("reference", percent, "");
    }
    void finish() {
        if (enabled_) std::fputs("\n", stderr);
    }

  private:
    bool enabled_;
    int last_ = -1;
};

}  // namespace

int runReferenceCommand(int argc, char** argv, int first) {
    auto parsed = referenceSpec().parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& args = *parsed;
    reference::ReferenceSettings settings;
    std::tie(settings.width, settings.height) = args.getSize("size", 16384);
    settings.seed = args.getUint("seed", 0, 0xFFFFFFFFu);
    settings.bounces = parseBounces(args.get("bounces"));
    const std::string secondary = args.get("secondary");
    if (secondary != "full" && secondary != "diffuse")
        throw UsageError("--secondary '" + secondary + "': expected full or diffuse");
    settings.secondary =
        secondary == "full" ? reference::SecondaryBrdf::Full : reference::SecondaryBrdf::Diffuse;
    settings.threads = args.getUint("threads", 0, 1024);
    settings.environment = RenderSettings{}.ambient;
    // The environment's four flags, as the table's rows parse them (applySettingArgs would also read this
    // command's own --bounces, which takes values the renderer's does not).
    RenderSettings renderSettings;
    if (args.has("environment")) renderSettings.environment = args.get("environment");
    renderSettings.environmentIntensity = args.getFloat("environment-intensity", 1e-3f, 1e4f);
    renderSettings.environmentRotation = args.getFloat("environment-rotation", -360.0f, 360.0f);
    renderSettings.skyTurbidity = args.getFloat("sky-turbidity", 2.0f, 10.0f);
    const uint32_t spp = args.getUint("spp", 1, 1u << 20);
    if (uint64_t(settings.width) * settings.height * spp > kMaxSamples)
        throw UsageError("--size " + args.get("size") + " with --spp " + std::to_string(spp) +
                         ": more than " + std::to_string(kMaxSamples) + " samples in all");
    const uint32_t frame = args.getUint("frame", 0, 1000000);
    const float exposure = args.getFloat("exposure", 1e-6f, 1e6f);
    const std::filesystem::path outDir = args.get("out");
    const std::optional<CameraPath> cameraPath =
        args.has("camera-path") ? std::optional<CameraPath>(loadCameraPath(args.get("camera-path")))
                                : std::nullopt;
    prepareOutputDirectory(outDir, "--out");

    const Scene scene = loadScene(args.get("scene"));
    printSceneNotes(scene, cameraPath ? args.get("camera-path") : "");
    if (cameraPath) checkCameraPathForScene(*cameraPath, scene, args.get("camera-path"));
    // The very frame `vct render --frames K+1` ends on: time and camera from the same function.
    const FrameInput input = fixedStepFrame(scene, frame, 0, cameraPath ? &*cameraPath : nullptr);
    settings.environmentMap = std::make_shared<const EnvironmentMap>(sceneEnvironment(scene, renderSettings));
    std::printf("environment: %s\n", settings.environmentMap->description.c_str());
    reference::PathTracer tracer(scene, input.timeSeconds, input.camera, settings);
    std::printf("reference: %s, %ux%u, %u spp, bounces %s, secondary %s, seed %u\n", scene.name.c_str(),
                settings.width, settings.height, spp, args.get("bounces").c_str(), secondary.c_str(),
                unsigned(settings.seed));
    ProgressBar bar(isatty(STDERR_FILENO) != 0);
    tracer.addSamples(spp, [&](float fraction) { bar.update(fraction); });
    bar.finish();

    const reference::ReferenceImages images = tracer.images();
    reference::ReferenceRunInfo info;
    info.scene = args.get("scene");
    info.frame = frame;
    info.timeSeconds = input.timeSeconds;
    info.cameraPath = args.get("camera-path");
    info.exposure = exposure;
    for (const std::string& name : reference::writeReferenceDirectory(outDir, tracer, images, info))
        std::printf("wrote %s\n", (outDir / name).c_str());
    const reference::ReferenceStats& stats = tracer.stats();
    std::printf("%llu rays in %.2f s: %.2f Mrays/s\n", static_cast<unsigned long long>(stats.rays),
                stats.seconds, stats.raysPerSecond() * 1e-6);
    return 0;
}

}  // namespace vct
