// bounce: multiple bounces of indirect light in the voxel grid (docs/design.md §5.7). After the frame's inject
// and mips hold the directly lit voxels, each of bounces − 1 iterations lets every occupied voxel gather the
// light arriving at it through the grid with the 6 diffuse cones (voxel_bounce.comp), then re-injects direct
// light + albedo × that (the inject pass, adding the gathered light) and rebuilds the mips: iteration k leaves
// light that has bounced k + 1 times in the grid, so the cones of the trace see bounces + 0 … bounces. Runs
// when the grid is rebuilt (the scene's geometry or lights changed), like inject; one timer scope, "bounce".
#pragma once

#include "passes/inject_pass.h"
#include "passes/voxel_mips_pass.h"
#include "render/gpu_environment.h"
#include "render/pass.h"
#include "render/voxel_grid.h"
#include "vk/pipeline.h"

namespace vct {

class VoxelBouncePass : public Pass {
  public:
    // `bounces` ≥ 2: the number of bounces the indirect light of a pixel carries (1 needs no pass).
    VoxelBouncePass(const vk::Context& context, VoxelGrid& grid, InjectPass& inject, VoxelMipsPass& mips,
                    uint32_t bounces, const EnvironmentSource& environment);
    const char* name() const override { return "bounce"; }
    void execute(const FrameContext& frame) override;
    PassReuse reuse() const override { return PassReuse::WhileSceneUnchanged; }

  private:
    VoxelGrid& grid_;
    InjectPass& inject_;
    VoxelMipsPass& mips_;
    uint32_t iterations_;
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
