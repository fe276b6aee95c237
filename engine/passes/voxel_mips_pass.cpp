#include "passes/voxel_mips_pass.h"

#include <algorithm>

#include "vk/barrier.h"

namespace vct {

namespace {

// Binding numbers: shaders/voxel_mips.comp's.
constexpr uint32_t kSource = 1, kDest = 2;

}  // namespace

VoxelMipsPass::VoxelMipsPass(const vk::Context& context, VoxelGrid& grid)
    : grid_(grid),
      // Both bindings are views of one level of the radiance texture, written per dispatch; the image stays
      // in GENERAL for the whole pass (read-write), ordered level by level by the memory barrier below.
      resources_("mips",
                 {{kSource, Resource::image("radiance", grid.radiance()).eachDispatch(), Access::Read},
                  {kDest, Resource::image("radiance", grid.radiance()).eachDispatch(), Access::Write}}) {
    pipeline_ = vk::Pipeline::compute(context, name(), "voxel_mips.comp", resources_.bindings(), 0);
}

void VoxelMipsPass::execute(const FrameContext& frame) {
    VkCommandBuffer cmd = frame.cmd;
    vk::Image& radiance = grid_.radiance();
    pipeline_.bind(cmd);
    resources_.barriers(frame);
    for (uint32_t level = 1; level < grid_.mipCount(); ++level) {
        if (level > 1) {
            // Level `level − 1`, written by the previous dispatch, is this dispatch's source: a dependency
            // between mip levels of one image, which the whole-image tracking of vk::Image does not express.
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                              VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                              VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
        }
        resources_.writer(frame)
            .storage(kSource, radiance.mipView(level - 1))
            .storage(kDest, radiance.mipView(level))
            .push(frame.context, cmd, pipeline_);
        const uint32_t size = std::max(1u, grid_.resolution() >> level);
        const uint32_t groups = voxelTileCount(size);
        // Six direction slabs side by side along x (lib/voxel.glsl).
        vkCmdDispatch(cmd, voxelTileCount(size * uint32_t(glsl::VOXEL_SLAB_COUNT)), groups, groups);
    }
}

}  // namespace vct
