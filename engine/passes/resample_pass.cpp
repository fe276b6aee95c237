#include "passes/resample_pass.h"

namespace vct {

namespace {

// Binding numbers: shaders/resample.comp's (1–3 the trace's, for the shared cone-tracing code).
ResourceTable resampleResources(const VoxelSource& voxels) {
    const Resource list = Resource::targetBuffer("resampleList", &FrameTargets::resampleList);
    std::vector<ResourceRow> rows{
        {VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
        {1, Target::depth, Access::Sampled},
        {2, Target::normalRoughness, Access::Sampled},
        // Read-write: only the listed pixels are written, the rest of the upsampled result must survive.
        {4, Target::indirect, Access::ReadWrite},
        // The list upsample made: this pass's indirect dispatch, its shader's input and a copy's source.
        {6, list, Access::Read},
        {kNoBinding, list, Access::IndirectRead},
        {kNoBinding, list, Access::TransferRead},
        {kNoBinding, Resource::targetBuffer("resampleCount", &FrameTargets::resampleCount),
         Access::TransferWrite}};
    voxels.addRows(rows, 3);
    voxels.environment.addRows(rows, 9);
    return {"resample", std::move(rows)};
}

}  // namespace

ResamplePass::ResamplePass(const vk::Context& context, uint32_t coneLanes, const VoxelSource& voxels)
    : resources_(resampleResources(voxels)) {
    // VCT_SPEC_CONE_LANES (constant 0, the trace scale, is not the resample's).
    pipeline_ = vk::Pipeline::compute(context, name(), "resample.comp", resources_.bindings(), 0,
                                      voxels.specialization({0u, coneLanes}));
}

void ResamplePass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    vkCmdDispatchIndirect(frame.cmd, t.resampleList.handle(), offsetof(gpu::ResampleListHeader, dispatch));

    // The entry count, for the host's `resampled_fraction` (read after the frame's fence).
    VkBufferCopy region{offsetof(gpu::ResampleListHeader, counts), 0, sizeof(uint32_t)};
    vkCmdCopyBuffer(frame.cmd, t.resampleList.handle(), t.resampleCount.handle(), 1, &region);
    t.resampleCount.use(frame.cmd, vk::BufferAccess::HostRead);
}

}  // namespace vct
