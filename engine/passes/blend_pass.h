// blend: glTF alphaMode BLEND surfaces, drawn forward after the opaque frame (docs/design.md §2.6). Sorted back
// to front per instance × primitive, depth-tested against the opaque depth without writing it, shaded at their
// own fragments as the opaque pixels are (direct light with the main light's shadow map, emission, cone-traced
// indirect light or with GI off the environment's) and composited "over" with premultiplied alpha into the
// transparent layer, which composite puts over the opaque frame.
#pragma once

#include "passes/trace_pass.h"
#include "render/dfg_lut.h"
#include "render/pass.h"
#include "render/scene_draw.h"
#include "vk/pipeline.h"

namespace vct {

class BlendPass : public Pass {
  public:
    // `voxels`: the grid's radiance (null with GI off: the fragments read the environment's light instead).
    // `vertexColors`: whether any primitive of the scene has COLOR_0 (VCT_SPEC_VERTEX_COLORS).
    // `dfg`: the split-sum table (the renderer's, shared with inject and composite). One pipeline per set of
    // textured slots of the blended materials on CPU devices (MaterialPipelines); `textureLod0`:
    // RenderSettings::textureLod0.
    BlendPass(const vk::Context& context, const VoxelSource* voxels, const EnvironmentSource& environment,
              DfgLut& dfg, const Scene& scene, bool vertexColors, bool textureLod0);
    const char* name() const override { return "blend"; }
    // Depends on the scene, the camera and the voxel grid, which changes only with the scene.
    PassReuse reuse() const override { return PassReuse::WhileViewUnchanged; }
    void execute(const FrameContext& frame) override;

  private:
    // GI off: a 1×1×2 volume and a 16-byte brick table the pipeline declares and never reads.
    vk::Image voxelStandIn_;
    vk::Image regionStandIn_;
    vk::Buffer brickStandIn_;
    ResourceTable resources_;
    MaterialPipelines pipelines_;
};

// The blended draws of the scene, back to front: by the view depth of each instance × primitive's world
// bounds centre, farthest first (ties keep the scene's order). What this cannot order correctly: primitives
// that intersect or interpenetrate, a large primitive whose centre lies behind a smaller one it is in front
// of (a long ground-hugging pane and a small one standing on it), and the triangles within one primitive
// (drawn in index order: a closed double-sided blended mesh shows its far side over its near side where the
// near side's triangles come first). Deformed instances are ordered by their rest bounds.
std::vector<DrawItem> blendedDrawsBackToFront(const GpuScene& scene, const glm::mat4& view);

}  // namespace vct
