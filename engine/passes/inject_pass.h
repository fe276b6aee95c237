// inject: direct light (main light shadow-mapped, other lights unshadowed) and emission into the occupied
// voxels → mip 0 of the grid's premultiplied radiance + opacity texture (docs/design.md §5.2); the bounce pass
// runs it again with the gathered light added (multiple bounces, §5.7).
#pragma once

#include "render/dfg_lut.h"
#include "render/pass.h"
#include "render/voxel_grid.h"
#include "vk/pipeline.h"

namespace vct {

class InjectPass : public Pass {
  public:
    // `dfg`: the split-sum table, for the specular lobes' directional albedo (docs/design.md §5.11).
    // `addBounce`: the frame's inject adds albedo × the light the voxels gathered (`--bounces all`, whose
    // gathers persist from frame to frame).
    InjectPass(const vk::Context& context, VoxelGrid& grid, DfgLut& dfg, bool addBounce = false);
    const char* name() const override { return "inject"; }
    void execute(const FrameContext& frame) override;
    // The direct light, plus with `addBounce` albedo × the light the voxels gathered (the bounce pass), into
    // `region` (brick-aligned; nullopt: the whole grid). The frame's own is VoxelGrid::injectRegion.
    void inject(const FrameContext& frame, bool addBounce, const std::optional<VoxelRegion>& region);
    PassReuse reuse() const override { return PassReuse::WhileSceneUnchanged; }

  private:
    VoxelGrid& grid_;
    bool addBounce_;
    ResourceTable resources_;
    // Mip 0 of the radiance as the clear before the dispatch writes it (one image cannot be a transfer
    // destination and a storage image in one table).
    ResourceTable clear_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
