// gbuffer: full-resolution depth, shading normal (normal-mapped) + roughness, base colour + metallic,
// emission + occlusion, and motion vectors (camera and moving objects).
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class GBufferPass : public Pass {
public:
    explicit GBufferPass(const vk::Context& context);
    const char* name() const override { return "gbuffer"; }
    PassReuse reuse() const override { return PassReuse::WhileViewUnchanged; }
    std::vector<ImageUse> uses(FrameTargets& targets) override;
    void execute(const FrameContext& frame) override;

private:
    vk::Pipeline pipeline_;
};

}  // namespace vct
