#include "app/session.h"

#include <cstdio>

#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace vct {

namespace {

// An on|off flag's value, or `fallback` when the flag is absent (or not declared by the command).
bool onOff(const ParsedArgs& args, const std::string& name, bool fallback) {
    if (!args.has(name)) return fallback;
    const std::string value = args.get(name);
    if (value == "on") return true;
    if (value == "off") return false;
    throw UsageError("--" + name + " '" + value + "': expected on or off");
}

}  // namespace

SessionOptions sessionOptions(const ParsedArgs& args) {
    SessionOptions options;
    options.scene = args.get("scene");
    // 16384 is the largest 2D image any current device allows; the device's own limit is checked too.
    auto [width, height] = args.getSize("size", 16384);
    options.settings.width = width;
    options.settings.height = height;
    options.settings.exposure = args.getFloat("exposure", 1e-4f, 1e4f);
    options.context.deviceSubstring = args.get("device");
    options.context.validation = args.has("validate");
    // Material filtering (docs/design.md §4): only commands that declare the flags (materialFilterOptions)
    // see them.
    options.settings.toksvig = onOff(args, "toksvig", options.settings.toksvig);
    options.settings.specularAA = onOff(args, "specular-aa", options.settings.specularAA);
    options.settings.textureLod0 = args.has("texture-lod0");
    if (args.has("anisotropy")) {
        const std::string value = args.get("anisotropy");
        if (value != "0" && value != "2" && value != "4" && value != "8" && value != "16")
            throw UsageError("--anisotropy '" + value + "': expected 0, 2, 4, 8 or 16");
        options.settings.anisotropy = uint32_t(std::stoul(value));
    }
    // Global illumination (docs/design.md §5), likewise only where declared (giOptions).
    options.settings.gi = onOff(args, "gi", options.settings.gi);
    if (args.has("trace-scale")) {
        const std::string value = args.get("trace-scale");
        if (value != "1" && value != "2" && value != "4")
            throw UsageError("--trace-scale '" + value + "': expected 1, 2 or 4");
        options.settings.traceScale = uint32_t(std::stoul(value));
    }
    options.settings.recomputeEveryFrame = args.has("recompute-every-frame");
    applyUpsampleOptions(args, options.settings);
    // 0 (flag absent) lets the renderer choose from the device (render/voxel_grid.h); N must be a power of two.
    if (args.has("voxels")) {
        options.settings.voxelResolution = args.getUint("voxels", 32, 256);
        if ((options.settings.voxelResolution & (options.settings.voxelResolution - 1)) != 0)
            throw UsageError("--voxels " + args.get("voxels") + ": expected a power of two (32, 64, 128 or 256)");
    }
    // The static voxelization from `vct voxelize --out FILE.vdb`; the file is read and checked by the renderer.
    if (args.has("voxel-cache")) {
        options.settings.voxelCache = args.get("voxel-cache");
        if (options.settings.voxelCache.empty()) throw UsageError("--voxel-cache: expected a file name");
        if (!options.settings.gi) throw UsageError("--voxel-cache needs --gi on (the voxels are for cone tracing)");
    }
    return options;
}

void applyUpsampleOptions(const ParsedArgs& args, RenderSettings& settings) {
    // Spatio-temporal upsampling and adaptive re-tracing (docs/design.md §6), where declared (upsampleOptions).
    if (args.has("weights")) {
        const std::string value = args.get("weights");
        if (value == "bilinear") settings.weights = RenderSettings::Weights::Bilinear;
        else if (value == "normal") settings.weights = RenderSettings::Weights::Normal;
        else if (value == "sg") settings.weights = RenderSettings::Weights::Sg;
        else throw UsageError("--weights '" + value + "': expected bilinear, normal or sg");
    }
    if (args.has("beta")) settings.beta = args.getFloat("beta", 0.01f, 1000.0f);
    if (args.has("kappa")) settings.kappa = args.getFloat("kappa", 0.01f, kMaxKappa);
    if (args.has("sigma-n")) settings.sigmaN = args.getFloat("sigma-n", 1e-3f, 10.0f);
    if (args.has("diffuse-sharpness")) settings.diffuseSharpness = args.getFloat("diffuse-sharpness", 1e-3f, 1e4f);
    if (args.has("gamma")) settings.gamma = args.getFloat("gamma", 0.0f, 1.0f);
    if (args.has("tau")) settings.tau = args.getFloat("tau", 1e-6f, 1000.0f);
    settings.temporal = onOff(args, "temporal", settings.temporal);
    settings.adaptive = onOff(args, "adaptive", settings.adaptive);
}

namespace {

// The defaults as the help prints them, read from RenderSettings (render/settings.h), the one place they live.
std::string text(float value) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", double(value));
    return buffer;
}
std::string onOffText(bool value) { return value ? "on" : "off"; }

}  // namespace

std::vector<Option> upsampleOptions() {
    const RenderSettings defaults;
    return {{"weights", "bilinear|normal|sg",
             "upsampling guide: none, depth x normal, depth x SG lobe (docs/design.md sec. 6.3)",
             weightsName(defaults.weights)},
            {"beta", "B", "SG lobe weight exponent", text(defaults.beta)},
            {"kappa", "K", "SG smoothing kernel sharpness (bounds every lobe's sharpness)", text(defaults.kappa)},
            {"sigma-n", "S", "normal weight width sigma_n (--weights normal)", text(defaults.sigmaN)},
            {"diffuse-sharpness", "L", "sg diffuse lobe sharpness lambda_d (--weights sg)", text(defaults.diffuseSharpness)},
            {"gamma", "G", "temporal history decay per frame (0..1)", text(defaults.gamma)},
            {"temporal", "on|off", "reproject and accumulate last frame's indirect light", onOffText(defaults.temporal)},
            {"tau", "T", "re-trace pixels whose sum of upsampling weights is below T", text(resampleThreshold(defaults))},
            {"adaptive", "on|off", "adaptive re-tracing of low-weight pixels at full resolution",
             onOffText(defaults.adaptive)}};
}

std::vector<Option> materialFilterOptions() {
    const RenderSettings defaults;
    return {{"toksvig", "on|off", "Toksvig roughness from normal-map mips (docs/design.md sec. 4.1)",
             onOffText(defaults.toksvig)},
            {"specular-aa", "on|off", "geometric specular anti-aliasing from normal derivatives",
             onOffText(defaults.specularAA)},
            {"texture-lod0", "", "diagnostic: sample material textures at level 0 only (supersampled references)",
             ""},
            {"anisotropy", "0|2|4|8|16",
             "anisotropic texture filtering (0: off); default 0 on a CPU device (very slow there), 8 on a GPU",
             ""}};
}

std::vector<Option> giOptions() {
    const RenderSettings defaults;
    return {{"gi", "on|off", "cone-traced indirect light; off: the constant ambient term instead", onOffText(defaults.gi)},
            {"trace-scale", "1|2|4", "trace indirect light at 1/S of the resolution per axis (1: every pixel)",
             std::to_string(defaults.traceScale)},
            {"voxels", "N", "voxel grid resolution N (N^3; 32, 64, 128 or 256); default 64 on a CPU device, 128 on a GPU",
             ""},
            {"voxel-cache", "FILE.vdb",
             "load the static voxelization from FILE (written by vct voxelize) instead of computing it", ""},
            {"recompute-every-frame", "",
             "diagnostic: run every pass every frame, also the shadow map, voxel grid, G-buffer and direct light "
             "when nothing moved, no light changed and the camera stood still",
             ""}};
}

Session::Session(const SessionOptions& options) {
    // The scene first: a bad file is reported before any Vulkan work.
    scene_ = loadScene(options.scene);
    for (const std::string& note : scene_.notes) std::printf("note: %s\n", note.c_str());
    context_ = std::make_unique<vk::Context>(options.context);
    std::printf("device: %s\n", context_->deviceName().c_str());
    renderer_ = std::make_unique<Renderer>(*context_, scene_, options.settings);
    printAnisotropy(options.settings.anisotropy, renderer_->settings().anisotropy);
}

void printAnisotropy(uint32_t requested, uint32_t chosen) {
    const char* why = requested == kAnisotropyFromDevice ? " (default for this device)"
                      : requested != chosen              ? " (the device's limit)"
                                                         : "";
    std::printf("anisotropy: %u%s\n", chosen, why);
}

Session::~Session() {
    renderer_.reset();
    context_.reset();
}

void checkValidation(const SessionOptions& options) {
    const uint32_t messages = vk::validationMessageCount();
    if (options.context.validation && messages > 0)
        throw Error(std::to_string(messages) + " validation message(s) reported (see stderr)");
}

}  // namespace vct
