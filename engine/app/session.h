// What both `render` and `demo` set up: the Vulkan context, the scene and the renderer, from common flags.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/cli.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "vk/context.h"

namespace vct {

struct SessionOptions {
    std::string scene = "cornell";
    RenderSettings settings;
    vk::ContextOptions context;
};

// Reads --scene, --size, --exposure, --device and --validate; --toksvig, --specular-aa (on|off) and
// --texture-lod0 when the command declares them.
SessionOptions sessionOptions(const ParsedArgs& args);

// The --toksvig and --specular-aa options (both default on), --anisotropy (0|2|4|8|16, default from the
// device) and the diagnostic --texture-lod0 switch, for a command's CommandSpec.
std::vector<Option> materialFilterOptions();

// The --gi (on|off) and --trace-scale (1|2|4) options, for a command's CommandSpec.
std::vector<Option> giOptions();
// The upsampling and adaptive re-tracing flags (--weights, --beta, --kappa, --sigma-n, --gamma, --temporal,
// --tau, --adaptive), and how they set RenderSettings (called by sessionOptions).
std::vector<Option> upsampleOptions();
void applyUpsampleOptions(const ParsedArgs& args, RenderSettings& settings);

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

// Throws when --validate was given and the validation layer reported anything.
void checkValidation(const SessionOptions& options);

}  // namespace vct
