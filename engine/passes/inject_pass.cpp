#include "passes/inject_pass.h"

namespace vct {

InjectPass::InjectPass(const vk::Context& context, VoxelGrid& grid, DfgLut& dfg, bool addBounce)
    : grid_(grid),
      addBounce_(addBounce),
      // Binding numbers: shaders/inject.comp's.
      resources_("inject",
                 {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
                  {1, Resource::scene(SceneBuffer::Lights), Access::Read},
                  {VCT_BINDING_BRICKS, Resource::buffer("bricks", grid.brickTable()), Access::Read},
                  {2, Resource::image("albedo", grid.albedo()), Access::Read},
                  {3, Resource::image("normal", grid.normal()), Access::Read},
                  {4, Resource::image("emission", grid.emission()), Access::Read},
                  {5, Target::shadowMap, Access::SampledCompare},
                  // Read-write, not write: a pure write would discard the clear before it (vk::Image::use).
                  {6, Resource::image("radianceAtlas", grid.radianceAtlas()), Access::ReadWrite},
                  {7, Resource::image("bounce", grid.bounce()), Access::Read},
                  // Mip 0 when dense (the shader writes one of the two: VCT_SPEC_SPARSE_MIP0).
                  {8, Resource::image("radianceMips", grid.radianceMips()).atLevel(0), Access::ReadWrite},
                  {9, Resource::image("dfg", dfg.image(), dfg.sampler()), Access::Sampled}}),
      clear_("inject clear",
             {{kNoBinding, Resource::image("mip0", grid.mip0Image()), Access::TransferWrite}}) {
    pipeline_ = vk::Pipeline::compute(context, name(), "inject.comp", resources_.bindings(),
                                      sizeof(gpu::InjectPushConstants),
                                      grid.specialization({voxelPassLanes(context)}));
}

void InjectPass::execute(const FrameContext& frame) {
    inject(frame, addBounce_, grid_.injectRegion());
}

void InjectPass::inject(const FrameContext& frame, bool addBounce, const std::optional<VoxelRegion>& region) {
    // Empty voxels are most of a brick: a clear (a memset on lavapipe) and stores only for the occupied voxels'
    // six slabs cost less than six stores of zero per empty voxel. A region's empty voxels are stored by the
    // shader instead (the rest of the atlas keeps the last frame's light).
    if (!region) {
        clear_.barriers(frame);
        const VkClearColorValue zero{};
        const VkImageSubresourceRange level0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(frame.cmd, grid_.mip0Image().handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             &zero, 1, &level0);
    }
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    const glm::uvec4 params(addBounce ? 1u : 0u, 0u, 0u, 0u);
    if (!region) {  // every allocated brick
        const gpu::InjectPushConstants push{params, glm::uvec4(0u)};
        pipeline_.pushConstants(frame.cmd, &push, sizeof(push));
        dispatchBricks(frame.cmd, grid_.bricks().brickCount());
        return;
    }
    const gpu::InjectPushConstants push{params, glm::uvec4(region->min, 1u)};
    pipeline_.pushConstants(frame.cmd, &push, sizeof(push));
    dispatchRegionBricks(frame.cmd, *region);
}

}  // namespace vct
