// skin: the deformation of skinned and morphed instances (docs/design.md §2.5), first in the frame: a compute
// pass that writes their morphed and skinned vertices into the deformed vertex buffer (render/gpu_deform.h),
// from which shadow, voxelize and gbuffer draw them (the static vertex buffer is untouched); last frame's
// deformed vertices are copied aside first, for the G-buffer's motion vectors. Made only for scenes that have
// such instances, and recording nothing in frames where their deformation stood still for two updates.
#pragma once

#include "render/gpu_deform.h"
#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class SkinPass : public Pass {
  public:
    SkinPass(const vk::Context& context, GpuDeform& deform);
    const char* name() const override { return "skin"; }
    void execute(const FrameContext& frame) override;

  private:
    GpuDeform& deform_;
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
