// composite: the frame's linear HDR result (direct; indirect joins in the cone-tracing issue) and its
// tone-mapped sRGB version for the PNG and the window.
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class CompositePass : public Pass {
public:
    explicit CompositePass(const vk::Context& context);
    const char* name() const override { return "composite"; }
    std::vector<ImageUse> uses(FrameTargets& targets) override;
    void execute(const FrameContext& frame) override;

private:
    vk::Pipeline pipeline_;
};

}  // namespace vct
