#include "passes/voxel_mips_pass.h"

#include <algorithm>

#include "vk/barrier.h"

namespace vct {

namespace {

// Binding numbers: shaders/voxel_mips.comp's.
constexpr uint32_t kSource = 1, kDest = 2, kAtlas = 3;

}  // namespace

VoxelMipsPass::VoxelMipsPass(const vk::Context& context, VoxelGrid& grid)
    : grid_(grid),
      // Source and destination are views of one level of the radiance mips, written per dispatch; the image
      // stays in GENERAL for the whole pass (read-write), ordered level by level by the memory barrier below.
      // Mip 1 reads mip 0 from the radiance atlas.
      resources_(
          "mips",
          {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
           {kSource, Resource::image("radianceMips", grid.radianceMips()).eachDispatch(), Access::Read},
           {kDest, Resource::image("radianceMips", grid.radianceMips()).eachDispatch(), Access::Write},
           {kAtlas, Resource::image("radianceAtlas", grid.radianceAtlas()), Access::Read},
           {VCT_BINDING_BRICKS, Resource::buffer("bricks", grid.brickTable()), Access::Read}}) {
    pipeline_ = vk::Pipeline::compute(context, name(), "voxel_mips.comp", resources_.bindings(),
                                      sizeof(gpu::VoxelMipsPushConstants), grid.specialization());
}

void VoxelMipsPass::execute(const FrameContext& frame) {
    update(frame, grid_.injectRegion());
}

void VoxelMipsPass::update(const FrameContext& frame, const std::optional<VoxelRegion>& updated) {
    VkCommandBuffer cmd = frame.cmd;
    vk::Image& radiance = grid_.radianceMips();
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
        // Mip m is the texture's level m − mipBase; a sparse mip 1 reads mip 0 from the atlas (the source binding
        // is then unused).
        const uint32_t base = grid_.mipBase();
        const bool fromAtlas = level == 1 && grid_.sparseMip0();
        resources_.writer(frame)
            .storage(kSource, radiance.mipView(fromAtlas ? 0 : level - 1 - base))
            .storage(kDest, radiance.mipView(level - base))
            .push(frame.context, cmd, pipeline_);
        // The texels with a child in the frame's region (the whole level without one), in each of the six
        // direction slabs side by side along x (lib/voxel.glsl).
        const uint32_t size = std::max(1u, grid_.resolution() >> level);
        const VoxelRegion region =
            updated ? updated->atLevel(level) : VoxelRegion{glm::uvec3(0), glm::uvec3(size)};
        if (region.empty()) continue;
        const glm::uvec3 extent = region.max - region.min;
        const gpu::VoxelMipsPushConstants push{glm::uvec4(region.min, extent.x),
                                               glm::uvec4(fromAtlas ? 1u : 0u, 0u, 0u, 0u)};
        pipeline_.pushConstants(cmd, &push, sizeof(push));
        vkCmdDispatch(cmd, voxelTileCount(extent.x * uint32_t(glsl::VOXEL_SLAB_COUNT)),
                      voxelTileCount(extent.y), voxelTileCount(extent.z));
    }
}

}  // namespace vct
