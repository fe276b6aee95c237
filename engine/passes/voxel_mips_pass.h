// mips: the radiance + opacity mip chain of the voxel grid, one dispatch per level (2×2×2 premultiplied
// average of the level above), with a barrier between levels. The timer scope is named "mips".
#pragma once

#include "render/pass.h"
#include "render/voxel_grid.h"
#include "vk/pipeline.h"

namespace vct {

class VoxelMipsPass : public Pass {
  public:
    VoxelMipsPass(const vk::Context& context, VoxelGrid& grid);
    const char* name() const override { return "mips"; }
    // The texels with a child in the frame's region (VoxelGrid::injectRegion), every level.
    void execute(const FrameContext& frame) override;
    // The same for `region` (nullopt: the whole grid), whatever the frame's.
    void update(const FrameContext& frame, const std::optional<VoxelRegion>& region);
    PassReuse reuse() const override { return PassReuse::WhileSceneUnchanged; }

  private:
    VoxelGrid& grid_;
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
