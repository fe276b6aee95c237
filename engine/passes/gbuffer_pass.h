// gbuffer: full-resolution depth, shading normal (normal-mapped) + roughness, base colour + metallic,
// emission + occlusion, and motion vectors (camera and moving objects).
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class GBufferPass : public Pass {
  public:
    // `vertexColors`: whether any primitive of the scene has COLOR_0 (VCT_SPEC_VERTEX_COLORS).
    GBufferPass(const vk::Context& context, bool vertexColors);
    const char* name() const override { return "gbuffer"; }
    PassReuse reuse() const override { return PassReuse::WhileViewUnchanged; }
    void execute(const FrameContext& frame) override;

  private:
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
