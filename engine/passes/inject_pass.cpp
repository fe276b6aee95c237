#include "passes/inject_pass.h"

namespace vct {

InjectPass::InjectPass(const vk::Context& context, VoxelGrid& grid)
    : grid_(grid),
      // Binding numbers: shaders/inject.comp's.
      resources_("inject",
                 {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
                  {1, Resource::scene(SceneBuffer::Lights), Access::Read},
                  {2, Resource::image("albedo", grid.albedo()), Access::Read},
                  {3, Resource::image("normal", grid.normal()), Access::Read},
                  {4, Resource::image("emission", grid.emission()), Access::Read},
                  {5, Target::shadowMap, Access::SampledCompare},
                  // Read-write, not write: a pure write would discard the clear before it (vk::Image::use).
                  {6, Resource::image("radiance", grid.radiance()).atLevel(0), Access::ReadWrite},
                  {7, Resource::image("bounce", grid.bounce()), Access::Read}}),
      clear_("inject clear",
             {{kNoBinding, Resource::image("radiance", grid.radiance()).atLevel(0), Access::TransferWrite}}) {
    pipeline_ = vk::Pipeline::compute(context, name(), "inject.comp", resources_.bindings(),
                                      sizeof(gpu::InjectPushConstants));
}

void InjectPass::execute(const FrameContext& frame) {
    inject(frame, false);
}

void InjectPass::inject(const FrameContext& frame, bool addBounce) {
    const std::optional<VoxelGrid::UpdateRegions>& regions = grid_.updateRegions();
    const uint32_t n = grid_.resolution();
    const VoxelRegion region = regions ? regions->inject : VoxelRegion{glm::uvec3(0), glm::uvec3(n)};
    // Empty voxels are most of a grid: a clear (a memset on lavapipe) and stores only for the occupied voxels'
    // six slabs cost less than six stores of zero per empty voxel. A region's empty voxels are stored by the
    // shader instead (the rest of the level keeps the last frame's light).
    if (!regions) {
        clear_.barriers(frame);
        const VkClearColorValue zero{};
        const VkImageSubresourceRange level0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(frame.cmd, grid_.radiance().handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             &zero, 1, &level0);
    }
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    const gpu::InjectPushConstants push{glm::uvec4(addBounce ? 1u : 0u, regions ? 1u : 0u, 0u, 0u),
                                        glm::uvec4(region.min, 0u)};
    pipeline_.pushConstants(frame.cmd, &push, sizeof(push));
    if (region.empty()) return;
    const glm::uvec3 size = region.max - region.min;
    vkCmdDispatch(frame.cmd, voxelTileCount(size.x), voxelTileCount(size.y), voxelTileCount(size.z));
}

}  // namespace vct
