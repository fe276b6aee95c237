// vct render: headless frames at a fixed 1/60 s step from t = 0; writes the last frame and the timings.
#include <cstdio>
#include <filesystem>

#include "app/aux_output.h"
#include "app/cli.h"
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/timings_json.h"

namespace vct {

namespace {

std::vector<Option> renderOptions() {
    std::vector<Option> options = {{"scene", "NAME|FILE", "built-in scene name (see vct scenes) or a .gltf/.glb file", "cornell"},
         {"size", "WxH", "image size in pixels", "1280x720"},
         {"frames", "N", "frames to render; the scene advances 1/60 s per frame from t = 0", "60"},
         {"warmup", "K", "frames left out of the timing statistics (default: min(10, frames/4))", ""},
         {"out", "DIR", "output directory (created if missing)", "out"},
         {"exposure", "X", "linear exposure before tone mapping", "1"},
         {"device", "SUBSTRING", "use the first Vulkan device whose name contains SUBSTRING", ""},
         {"validate", "", "enable the Khronos validation layer; any message fails the run", ""},
         {"aux", "", "also write every buffer as EXR: direct, normal, roughness, albedo, depth (and indirect)", ""},
         {"view", "BUFFER", "what final.png shows: final, direct, diffuse, specular, normals, roughness", "final"}};
    for (Option& option : materialFilterOptions()) options.push_back(std::move(option));
    for (Option& option : giOptions()) options.push_back(std::move(option));
    return options;
}

const CommandSpec& renderSpec() {
    static const CommandSpec spec(
        "render", "Renders frames headless (no window) and writes DIR/final.png, DIR/final.exr, DIR/timings.json.",
        renderOptions());
    return spec;
}

}  // namespace

int runRenderCommand(int argc, char** argv, int first) {
    auto parsed = renderSpec().parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& args = *parsed;
    SessionOptions options = sessionOptions(args);
    const uint32_t frames = args.getUint("frames", 1, 100000);
    const uint32_t warmup = args.has("warmup") ? args.getUint("warmup", 0, frames - 1) : std::min(10u, frames / 4);
    const std::filesystem::path outDir = args.get("out");
    const AuxView view = parseAuxView(args.get("view"));

    {
        Session session(options);
        std::error_code error;
        std::filesystem::create_directories(outDir, error);
        if (error) throw Error("cannot create output directory '" + outDir.string() + "': " + error.message());

        Renderer& renderer = session.renderer();
        for (uint32_t frame = 0; frame < frames; ++frame) {
            const float time = float(frame) / 60.0f;
            FrameInput input;
            input.camera = sceneCamera(session.scene(), time);
            input.timeSeconds = time;
            input.cut = frame == 0;
            input.recordTimings = frame >= warmup;
            renderer.render(input);
        }

        const uint32_t w = renderer.settings().width, h = renderer.settings().height;
        writePng(outDir / "final.png", w, h, viewImage(renderer, view));
        writeExr(outDir / "final.exr", w, h, renderer.readFloatImage(renderer.targets().hdr));

        TimingReport report;
        report.device = session.context().deviceName();
        report.width = w;
        report.height = h;
        report.frames = frames;
        report.warmup = warmup;
        report.passes = renderer.timer().passStats();
        report.frame = renderer.timer().frameStats();
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
