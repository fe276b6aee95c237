#include "passes/voxel_bounce_pass.h"

#include "passes/voxel_source.h"

namespace vct {

namespace {

// Binding numbers: shaders/voxel_bounce.comp's.
ResourceTable bounceResources(VoxelGrid& grid, const EnvironmentSource& environment) {
    std::vector<ResourceRow> rows{
        {VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
        {1, Resource::image("albedo", grid.albedo()), Access::Read},
        {2, Resource::image("normal", grid.normal()), Access::Read},
        {4, Resource::image("bounce", grid.bounce()), Access::Write},
        // Cones that leave the grid see the environment: sky light bounces too.
        {5, Resource::image("environment", *environment.image, environment.sampler), Access::Sampled}};
    VoxelSource::of(grid).addRows(rows, 3);
    return {"bounce", std::move(rows)};
}

}  // namespace

VoxelBouncePass::VoxelBouncePass(const vk::Context& context, VoxelGrid& grid, InjectPass& inject,
                                 VoxelMipsPass& mips, uint32_t bounces, const EnvironmentSource& environment)
    : grid_(grid),
      inject_(inject),
      mips_(mips),
      iterations_(bounces > 1 ? bounces - 1 : 0),
      resources_(bounceResources(grid, environment)) {
    pipeline_ = vk::Pipeline::compute(context, name(), "voxel_bounce.comp", resources_.bindings(), 0,
                                      grid.specialization());
}

void VoxelBouncePass::execute(const FrameContext& frame) {
    for (uint32_t i = 0; i < iterations_; ++i) {
        // Gather from the grid as it stands (its mips included)...
        pipeline_.bind(frame.cmd);
        resources_.bind(frame, pipeline_);
        dispatchBricks(frame.cmd, grid_.bricks().brickCount());
        // ...and send it on: direct light + albedo × gathered, and the mips of that.
        inject_.inject(frame, true);
        mips_.execute(frame);
    }
}

}  // namespace vct
