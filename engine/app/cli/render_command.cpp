// vct render: headless frames at a fixed 1/60 s step from t = 0; writes the last frame and the timings.
#include <bit>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "app/cli/aux_output.h"
#include "app/cli/cli.h"
#include "app/cli/commands.h"
#include "app/cli/session.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/safe_write.h"
#include "report/timings_json.h"
#include "scene/camera_path.h"

namespace vct {

namespace {

std::vector<Option> renderOptions() {
    std::vector<Option> options = {
        {"scene", "NAME|FILE", "built-in scene name (see vct scenes) or a .gltf/.glb file", "cornell"},
        settingOption("size"),
        {"frames", "N", "frames to render; the scene advances 1/60 s per frame from t = 0", "60"},
        {"warmup", "K", "frames left out of the timing statistics (default: min(10, frames/4))", ""},
        {"out", "DIR", "output directory (created if missing)", "out"},
        settingOption("exposure"),
        {"device", "SUBSTRING", "use the first Vulkan device whose name contains SUBSTRING", ""},
        {"camera-path", "FILE.json",
         "play this keyframed camera path (scenes/*.camera.json) instead of the scene camera", ""},
        {"camera-cut", "K", "from frame K on, the camera jumps to another view (a camera cut: no history)",
         ""},
        {"validate", "", "enable the Khronos validation layer; any message fails the run", ""},
        {"aux", "", "also write every buffer as EXR: direct, normal, roughness, albedo, depth (and indirect)",
         ""},
        {"view", "BUFFER",
         "what final.png shows: final, direct, diffuse, specular, normals, roughness, voxels, resample "
         "(re-traced pixels in red), weights (sum of upsampling weights)",
         "final"},
        {"voxel-mip", "M", "--view voxels: ray-march the voxel grid at mip M (0 .. log2(N))", "0"}};
    for (SettingGroup group : {SettingGroup::Material, SettingGroup::Gi, SettingGroup::Upsample})
        for (Option& option : settingOptions(group)) options.push_back(std::move(option));
    return options;
}

const CommandSpec& renderSpec() {
    static const CommandSpec spec(
        "render",
        "Renders frames headless (no window) and writes DIR/final.png, DIR/final.exr, DIR/timings.json.",
        renderOptions());
    return spec;
}

}  // namespace

int runRenderCommand(int argc, char** argv, int first) {
    auto parsed = renderSpec().parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& args = *parsed;
    SessionOptions options = sessionOptions(args);
    if (args.has("camera-path")) options.cameraPath = args.get("camera-path");
    const uint32_t frames = args.getUint("frames", 1, 100000);
    const uint32_t warmup =
        args.has("warmup") ? args.getUint("warmup", 0, frames - 1) : std::min(10u, frames / 4);
    const std::filesystem::path outDir = args.get("out");
    const AuxView view = parseAuxView(args.get("view"));
    const std::optional<CameraPath> cameraPath =
        args.has("camera-path") ? std::optional<CameraPath>(loadCameraPath(args.get("camera-path")))
                                : std::nullopt;
    const uint32_t cutFrame = args.has("camera-cut") ? args.getUint("camera-cut", 1, frames - 1) : frames;
    // --voxel-mip M: 0 .. mipCount − 1 of the grid (log2(N) + 1 mips), checked before any frame is rendered.
    if (args.has("voxel-mip") && view != AuxView::Voxels)
        throw UsageError("--voxel-mip: only with --view voxels");
    if (view == AuxView::Voxels && !options.settings.gi)
        throw UsageError("--view voxels: there is no voxel grid with --gi off");
    // The per-pixel sum of upsampling weights is an output of its own, written only when something shows it.
    options.settings.writeWeightSum =
        args.has("aux") || view == AuxView::Weights || view == AuxView::Resample;
    // Checked before any frame: with GI off the frame has no indirect light, weights or re-traced pixels.
    if (auxViewNeedsGi(view) && !options.settings.gi)
        throw UsageError(std::string("--view ") + auxViewName(view) +
                         ": needs --gi on (no indirect light with --gi off)");
    auto voxelMip = [&](uint32_t mipCount) { return args.getUint("voxel-mip", 0, mipCount - 1); };
    if (view == AuxView::Voxels && options.settings.voxelResolution != 0)
        voxelMip(uint32_t(std::bit_width(options.settings.voxelResolution)));

    // Before any work: an --out that cannot take the files would otherwise fail after the last frame.
    prepareOutputDirectory(outDir, "--out");
    {
        Session session(options);
        if (cameraPath) checkCameraPathForScene(*cameraPath, session.scene(), args.get("camera-path"));

        Renderer& renderer = session.renderer();
        const uint32_t mip = view == AuxView::Voxels ? voxelMip(renderer.voxelGrid()->mipCount()) : 0;
        for (uint32_t frame = 0; frame < frames; ++frame) {
            FrameInput input =
                fixedStepFrame(session.scene(), frame, warmup, cameraPath ? &*cameraPath : nullptr);
            if (frame == cutFrame) input.cut = true;
            if (frame >= cutFrame) input.camera = cutCamera(input.camera);
            renderer.render(input);
        }

        const uint32_t w = renderer.settings().width, h = renderer.settings().height;
        writePng(outDir / "final.png", w, h, viewImage(renderer, view, mip));
        writeFinalExr(renderer, outDir / "final.exr");

        TimingReport report;
        report.device = session.context().deviceName();
        report.width = w;
        report.height = h;
        report.frames = frames;
        report.warmup = warmup;
        report.anisotropy = renderer.settings().anisotropy;
        report.settings = renderer.settings();
        report.passes = renderer.timer().passStats();
        report.frame = renderer.timer().frameStats();
        report.resampledFraction = renderer.resampledFraction();
        report.voxels = voxelStorageReport(renderer);
        report.shadowTexels = renderer.shadowTexels();
        report.shadowTexelsRedrawn = renderer.shadowTexelsRedrawn();
        report.directPartial = renderer.directLightPartial();
        report.directPixelsDispatched = renderer.directPixelsDispatched();
        report.gbufferPixelsRedrawn = renderer.gbufferPixelsRedrawn();
        writeTimingsJson(outDir / "timings.json", report);
        if (args.has("aux"))
            for (const std::string& name : writeAuxImages(renderer, outDir))
                std::printf("wrote %s\n", (outDir / name).c_str());
        std::printf("%s", formatTimingTable(report).c_str());
        std::printf("wrote %s, %s, %s\n", (outDir / "final.png").c_str(), (outDir / "final.exr").c_str(),
                    (outDir / "timings.json").c_str());
    }
    // Counted after the device is destroyed, so leaks reported at teardown fail the run too.
    checkValidation(options);
    return 0;
}

}  // namespace vct
