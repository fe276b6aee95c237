#include "passes/trace_pass.h"

namespace vct {

namespace {

// Binding numbers: shaders/trace.comp's.
ResourceTable traceResources(Target output, const VoxelSource& voxels) {
    std::vector<ResourceRow> rows{
        {VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
        {1, Target::depth, Access::Sampled},
        {2, Target::normalRoughness, Access::Sampled},
        {4, output, Access::Write},
        // 1×1 stand-ins at trace scale 1 (the pipeline declares them, never writes them).
        {6, Target::guidePosition, Access::Write},
        {7, Target::guideNormal, Access::Write},
        {8, Target::guideAxis, Access::Write},
        {9, Resource::image("environment", *voxels.environment.image, voxels.environment.sampler),
         Access::Sampled},
        // Trace scale 1: the history its sample is added to (trace.comp, accumulateHistory).
        {10, Target::motion, Access::Sampled},
        {11, Target::prevDepth, Access::Sampled},
        {12, Target::prevNormalRoughness, Access::Sampled},
        {13, Target::indirectHistory, Access::Sampled}};
    voxels.addRows(rows, 3);
    return {"trace", std::move(rows)};
}

}  // namespace

uint32_t traceConeLanes(const vk::Context& context, RenderSettings::TraceLayout layout) {
    using Layout = RenderSettings::TraceLayout;
    const bool cones = layout == Layout::Cone || (layout == Layout::Auto && context.properties().deviceType !=
                                                                                VK_PHYSICAL_DEVICE_TYPE_CPU);
    return cones ? VCT_CONE_LANES_PER_PIXEL : 1u;
}

TracePass::TracePass(const vk::Context& context, uint32_t traceScale, uint32_t coneLanes,
                     const VoxelSource& voxels)
    : output_(traceScale <= 1 ? Target::indirect : Target::indirectLow),
      resources_(traceResources(output_, voxels)) {
    // VCT_SPEC_TRACE_SCALE, VCT_SPEC_CONE_LANES
    pipeline_ = vk::Pipeline::compute(context, name(), "trace.comp", resources_.bindings(), 0,
                                      voxels.specialization({traceScale, coneLanes}));
}

void TracePass::execute(const FrameContext& frame) {
    const vk::Image& output = frame.targets.image(output_);
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    vkCmdDispatch(frame.cmd, tileCount(output.width()), tileCount(output.height()), 1);
}

}  // namespace vct
