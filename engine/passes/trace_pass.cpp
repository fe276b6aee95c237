#include "passes/trace_pass.h"

#include <algorithm>
#include <string>

#include "core/error.h"

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
        // Trace scale 1: the history its sample is added to (trace.comp, accumulateHistory).
        {10, Target::motion, Access::Sampled},
        {11, Target::prevDepth, Access::Sampled},
        {12, Target::prevNormalRoughness, Access::Sampled},
        {13, Target::indirectHistory, Access::Sampled}};
    voxels.addRows(rows, 3);
    voxels.environment.addRows(rows, 9);
    return {"trace", std::move(rows)};
}

}  // namespace

uint32_t traceConeLanes(const vk::Context& context, RenderSettings::TraceLayout layout) {
    using Layout = RenderSettings::TraceLayout;
    // The cone layout's largest workgroup: the trace's tile, the resample's entries or the bounce's brick (one
    // voxel an invocation on a GPU), times the cones. Vulkan guarantees 128 invocations and a z size of 64; a
    // device that allows fewer than this keeps the pixel layout (or refuses it when asked for).
    constexpr uint32_t kGroupInvocations =
        std::max({uint32_t(VCT_TILE_SIZE * VCT_TILE_SIZE), uint32_t(VCT_RESAMPLE_GROUP_SIZE),
                  uint32_t(VCT_VOXEL_BRICK * VCT_VOXEL_BRICK * VCT_VOXEL_BRICK)}) *
        VCT_CONE_LANES_PER_PIXEL;
    const VkPhysicalDeviceLimits& limits = context.properties().limits;
    const bool fits = limits.maxComputeWorkGroupInvocations >= kGroupInvocations &&
                      limits.maxComputeWorkGroupSize[2] >= VCT_CONE_LANES_PER_PIXEL;
    if (layout == Layout::Cone && !fits)
        throw UsageError(
            "--trace-layout cone: needs " + std::to_string(kGroupInvocations) +
            " invocations per workgroup, more than this device's maxComputeWorkGroupInvocations (" +
            std::to_string(limits.maxComputeWorkGroupInvocations) + "); use --trace-layout pixel");
    const bool gpu = context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU;
    return layout == Layout::Cone || (layout == Layout::Auto && fits && gpu) ? VCT_CONE_LANES_PER_PIXEL : 1u;
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
