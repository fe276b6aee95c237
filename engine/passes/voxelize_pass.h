// voxelize: scene triangles → the voxel grid's albedo + opacity, normal and emission volumes (docs/design.md
// §5.1). A compute pass over triangles (no conservative rasterization on lavapipe): static instances are
// voxelized once, on the first frame, into a persistent accumulator; moving instances every frame into a second
// one, cleared first; a resolve merges both into the volumes. One timer scope covers all of it. With a voxel
// cache (--voxel-cache, VoxelGrid::loadStaticCache) the first frame copies the cached static accumulator instead
// of voxelizing the static instances: the same uints, so the same image.
#pragma once

#include "render/pass.h"
#include "render/voxel_grid.h"
#include "vk/pipeline.h"

namespace vct {

class VoxelizePass : public Pass {
  public:
    VoxelizePass(const vk::Context& context, VoxelGrid& grid);
    const char* name() const override { return "voxelize"; }
    void execute(const FrameContext& frame) override;
    PassReuse reuse() const override { return PassReuse::WhileSceneUnchanged; }

  private:
    // Dispatches the triangles of every instance whose `moving` flag equals `moving` into `accumulator`.
    void voxelizeInstances(const FrameContext& frame, bool moving, const vk::Buffer& accumulator);

    VoxelGrid& grid_;
    ResourceTable voxelizeResources_, resolveResources_;
    vk::Pipeline voxelize_, resolve_;
    bool resolved_ = false;  // the volumes hold the current accumulators
};

}  // namespace vct
