// voxel view (`vct render --view voxels`): the voxel grid ray-marched at one mip from the frame's camera
// (shaders/voxel_view.comp: a DDA over that level's texels, front-to-back compositing of premultiplied radiance
// + opacity, plus a little grey so that unlit voxels show). Run on demand after a frame by
// Renderer::renderVoxelView, never in the frame's pass list: normal frames do not pay for it.
#pragma once

#include "render/pass.h"
#include "render/voxel_grid.h"
#include "vk/pipeline.h"

namespace vct {

class VoxelViewPass : public Pass {
  public:
    VoxelViewPass(const vk::Context& context, VoxelGrid& grid);
    const char* name() const override { return "voxel_view"; }
    void execute(const FrameContext& frame) override;

    // The mip level to march (0 .. grid.mipCount() − 1) and the output's size (the frame's); call before
    // execute().
    void prepare(uint32_t mip, uint32_t width, uint32_t height);
    // Radiance seen through the grid, RGBA16F (rgb; a = 1), at the size given to prepare().
    vk::Image& output() { return output_; }

  private:
    const vk::Context& context_;
    VoxelGrid& grid_;
    vk::Image output_;  // before resources_, which names it
    ResourceTable resources_;
    vk::Pipeline pipeline_;
    uint32_t mip_ = 0;
};

}  // namespace vct
