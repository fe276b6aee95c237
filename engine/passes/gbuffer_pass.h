// gbuffer: full-resolution depth, shading normal (normal-mapped) + roughness, base colour + metallic,
// emission + occlusion, and motion vectors (camera and moving objects).
#pragma once

#include "render/pass.h"
#include "render/scene_draw.h"
#include "vk/pipeline.h"

namespace vct {

class GBufferPass : public Pass {
  public:
    // `vertexColors`: whether any primitive of the scene has COLOR_0 (VCT_SPEC_VERTEX_COLORS). One pipeline per
    // set of textured slots of the scene's materials on CPU devices (MaterialPipelines); `textureLod0`:
    // RenderSettings::textureLod0.
    GBufferPass(const vk::Context& context, const Scene& scene, bool vertexColors, bool textureLod0);
    const char* name() const override { return "gbuffer"; }
    PassReuse reuse() const override { return PassReuse::WhileViewUnchanged; }
    void execute(const FrameContext& frame) override;

  private:
    vk::Pipeline::GraphicsDesc pipelineDesc(bool vertexColors) const;
    ResourceTable resources_;
    MaterialPipelines pipelines_;
};

}  // namespace vct
