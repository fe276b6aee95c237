#include "app/cli/session.h"

#include <cstdint>
#include <cstdio>

#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace vct {

SessionOptions sessionOptions(const ParsedArgs& args) {
    SessionOptions options;
    options.scene = args.get("scene");
    options.context.deviceSubstring = args.get("device");
    options.context.validation = args.has("validate");
    applySettingArgs(args, options.settings);
    // Each side may be as large as a device allows; both together ask for gigabytes of targets, and per-pixel
    // storage buffers of 8 bytes a pixel: 2^25 pixels (8192x4096) already exceed lavapipe's 128 MiB
    // maxStorageBufferRange (validation messages), 2^24 do not.
    constexpr uint64_t kMaxFramePixels = uint64_t(1) << 24;  // 4096 x 4096
    const uint64_t pixels = uint64_t(options.settings.width) * options.settings.height;
    if (pixels > kMaxFramePixels)
        throw UsageError("--size " + std::to_string(options.settings.width) + "x" +
                         std::to_string(options.settings.height) + ": " + std::to_string(pixels) +
                         " pixels, more than the " + std::to_string(kMaxFramePixels) +
                         " (4096x4096) a frame may have");
    // The static voxelization from `vct voxelize --out FILE.vdb`; the file is read and checked by the renderer.
    if (!options.settings.voxelCache.empty() && !options.settings.gi)
        throw UsageError("--voxel-cache needs --gi on (the voxels are for cone tracing)");
    return options;
}

void applySettingArgs(const ParsedArgs& args, RenderSettings& settings) {
    for (const SettingSpec& spec : settingTable()) {
        if (spec.group == SettingGroup::Internal) continue;
        const std::string value =
            args.get(spec.name);  // the value given, else the command's default, else ""
        if (!args.has(spec.name) && value.empty()) continue;
        parseSetting(spec, value, std::string("--") + spec.name, settings);
    }
}

Option settingOption(std::string_view name) {
    const SettingSpec* spec = findSetting(name);
    if (!spec || spec->group == SettingGroup::Internal)
        throw Error("settingOption: '" + std::string(name) + "' is not a setting of the command line");
    return {spec->name, spec->valueName, spec->help, settingDefaultText(*spec)};
}

std::vector<Option> settingOptions(SettingGroup group) {
    std::vector<Option> options;
    for (const SettingSpec& spec : settingTable())
        if (spec.group == group) options.push_back(settingOption(spec.name));
    return options;
}

Session::Session(const SessionOptions& options) {
    // The scene first: a bad file is reported before any Vulkan work.
    scene_ = loadScene(options.scene);
    printSceneNotes(scene_, options.cameraPath);
    context_ = std::make_unique<vk::Context>(options.context);
    std::printf("device: %s\n", context_->deviceName().c_str());
    renderer_ = std::make_unique<Renderer>(*context_, scene_, options.settings);
    printAnisotropy(options.settings.anisotropy, renderer_->settings().anisotropy);
    std::printf("environment: %s\n", renderer_->environment().description.c_str());
}

void printSceneNotes(const Scene& scene, const std::string& cameraPath) {
    for (const std::string& note : scene.notes)
        if (cameraPath.empty() || note != kDefaultCameraNote)
            std::printf("note: %s\n", note.c_str());
        else
            std::printf("note: scene has no camera: the camera follows %s\n", cameraPath.c_str());
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
