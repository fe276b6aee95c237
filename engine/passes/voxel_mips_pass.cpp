#include "passes/voxel_mips_pass.h"

#include <algorithm>

#include "vk/barrier.h"

namespace vct {

VoxelMipsPass::VoxelMipsPass(const vk::Context& context, VoxelGrid& grid) : grid_(grid) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_ = vk::Pipeline::compute(context, "voxel_mips.comp",
                                      {{VCT_MIPS_BINDING_SOURCE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs},
                                       {VCT_MIPS_BINDING_DEST, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs}},
                                      0);
}

// All levels stay in GENERAL for the whole pass; the per-level dependency is a memory barrier below.
std::vector<ImageUse> VoxelMipsPass::uses(FrameTargets&) {
    return {{&grid_.radiance(), vk::ImageAccess::StorageReadWrite}};
}

void VoxelMipsPass::execute(const FrameContext& frame) {
    VkCommandBuffer cmd = frame.cmd;
    vk::Image& radiance = grid_.radiance();
    pipeline_.bind(cmd);
    for (uint32_t level = 1; level < grid_.mipCount(); ++level) {
        if (level > 1) {
            // Level `level − 1`, written by the previous dispatch, is this dispatch's source.
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                              VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
        }
        vk::DescriptorWriter()
            .storage(VCT_MIPS_BINDING_SOURCE, radiance.mipView(level - 1))
            .storage(VCT_MIPS_BINDING_DEST, radiance.mipView(level))
            .push(frame.context, cmd, pipeline_);
        const uint32_t size = std::max(1u, grid_.resolution() >> level);
        const uint32_t groups = (size + VCT_VOXEL_TILE - 1) / VCT_VOXEL_TILE;
        vkCmdDispatch(cmd, groups, groups, groups);
    }
}

}  // namespace vct
