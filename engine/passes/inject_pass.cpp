#include "passes/inject_pass.h"

namespace vct {

InjectPass::InjectPass(const vk::Context& context, VoxelGrid& grid)
    : grid_(grid),
      // Binding numbers: shaders/inject.comp's.
      resources_("inject", {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
                            {1, Resource::scene(SceneBuffer::Lights), Access::Read},
                            {2, Resource::image("albedo", grid.albedo()), Access::Read},
                            {3, Resource::image("normal", grid.normal()), Access::Read},
                            {4, Resource::image("emission", grid.emission()), Access::Read},
                            {5, Target::shadowMap, Access::SampledCompare},
                            {6, Resource::image("radiance", grid.radiance()).atLevel(0), Access::Write},
                            {7, Resource::image("bounce", grid.bounce()), Access::Read}}) {
    pipeline_ = vk::Pipeline::compute(context, name(), "inject.comp", resources_.bindings(),
                                      sizeof(gpu::InjectPushConstants));
}

void InjectPass::execute(const FrameContext& frame) {
    inject(frame, false);
}

void InjectPass::inject(const FrameContext& frame, bool addBounce) {
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    const gpu::InjectPushConstants push{glm::uvec4(addBounce ? 1u : 0u, 0u, 0u, 0u)};
    pipeline_.pushConstants(frame.cmd, &push, sizeof(push));
    const uint32_t groups = voxelTileCount(grid_.resolution());
    vkCmdDispatch(frame.cmd, groups, groups, groups);
}

}  // namespace vct
