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
                            {6, Resource::image("radiance", grid.radiance()).atLevel(0), Access::Write}}) {
    pipeline_ = vk::Pipeline::compute(context, name(), "inject.comp", resources_.bindings(), 0);
}

void InjectPass::execute(const FrameContext& frame) {
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    const uint32_t groups = (grid_.resolution() + VCT_VOXEL_TILE - 1) / VCT_VOXEL_TILE;
    vkCmdDispatch(frame.cmd, groups, groups, groups);
}

}  // namespace vct
