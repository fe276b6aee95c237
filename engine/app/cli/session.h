// What both `render` and `demo` set up: the Vulkan context, the scene and the renderer, from common flags.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "app/cli/cli.h"
#include "render/renderer.h"
#include "render/setting_table.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace vct {

struct SessionOptions {
    std::string scene = "cornell";
    std::string cameraPath;  // --camera-path FILE, when the frames' camera comes from one
    RenderSettings settings;
    vk::ContextOptions context;
};

// Reads --scene, --device, --validate and every setting of the table (render/setting_table.h) that the
// command declares: those given on the command line, and those the command gives a default.
SessionOptions sessionOptions(const ParsedArgs& args);

// The flags of the setting table's rows in `group`, in table order, with their help and their defaults from
// RenderSettings{} (SettingGroup::Gi, Upsample and Material for render and demo; Material for benchmark).
std::vector<Option> settingOptions(SettingGroup group);
// The flag of one row, for a command that takes it alone (--size, --exposure, --voxels); the command may
// change the default (benchmark's --size) or add to the help.
Option settingOption(std::string_view name);
// Sets, in table order, every row whose flag the command declares and the command line gives, or the command
// gives a default for (its --help default): the one parser of settings on the command line.
void applySettingArgs(const ParsedArgs& args, RenderSettings& settings);

class Session {
  public:
    explicit Session(const SessionOptions& options);
    ~Session();
    vk::Context& context() { return *context_; }
    const Scene& scene() const { return scene_; }
    Renderer& renderer() { return *renderer_; }

  private:
    Scene scene_;
    std::unique_ptr<vk::Context> context_;
    std::unique_ptr<Renderer> renderer_;
};

// The startup line naming the anisotropic filtering level in use, like the device line: `requested` is the
// setting given to the Renderer (kAnisotropyFromDevice without --anisotropy), `chosen` the Renderer's.
void printAnisotropy(uint32_t requested, uint32_t chosen);

// Prints the scene's notes ("note: ..."), one a line; with a camera path (the file given to --camera-path)
// the default-camera note of a scene without a camera says that the path is the camera instead.
void printSceneNotes(const Scene& scene, const std::string& cameraPath = "");

// Throws when --validate was given and the validation layer reported anything.
void checkValidation(const SessionOptions& options);

}  // namespace vct
