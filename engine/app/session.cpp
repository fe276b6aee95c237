#include "app/session.h"

#include <cstdio>

#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace vct {

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
    return options;
}

Session::Session(const SessionOptions& options) {
    // The scene first: a bad file is reported before any Vulkan work.
    scene_ = loadScene(options.scene);
    for (const std::string& note : scene_.notes) std::printf("note: %s\n", note.c_str());
    context_ = std::make_unique<vk::Context>(options.context);
    std::printf("device: %s\n", context_->deviceName().c_str());
    renderer_ = std::make_unique<Renderer>(*context_, scene_, options.settings);
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
