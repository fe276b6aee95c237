#include "passes/upsample_pass.h"

#include "render/shader_math.h"

namespace vct {

UpsamplePass::UpsamplePass(const vk::Context& context)
    : context_(context),
      // Binding numbers: shaders/upsample.comp's.
      resources_("upsample", {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
                              {1, Target::indirectLow, Access::Sampled},
                              {3, Target::indirect, Access::Write},
                              {5, Target::depth, Access::Sampled},
                              {6, Target::normalRoughness, Access::Sampled},
                              {7, Target::motion, Access::Sampled},
                              {8, Target::prevDepth, Access::Sampled},
                              {9, Target::prevNormalRoughness, Access::Sampled},
                              {10, Target::indirectHistory, Access::Sampled},
                              {12, Target::weightSum, Access::Write},
                              // Cleared here first (execute), appended to by the shader.
                              {13, Resource::targetBuffer("resampleList", &FrameTargets::resampleList),
                               Access::ReadWrite},
                              {14, Target::guidePosition, Access::Sampled},
                              {15, Target::guideNormal, Access::Sampled},
                              {16, Target::guideAxis, Access::Sampled}}) {}

bool UpsamplePass::perPixel(const RenderSettings& settings) const {
    using Layout = RenderSettings::UpsampleLayout;
    if (settings.traceScale < 2) return false;
    return settings.upsampleLayout == Layout::Pixel ||
           (settings.upsampleLayout == Layout::Auto &&
            context_.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU);
}

const vk::Pipeline& UpsamplePass::pipelineFor(const RenderSettings& settings, uint32_t width,
                                              uint32_t height) {
    const uint32_t weights = settings.weights == RenderSettings::Weights::Bilinear ? VCT_WEIGHTS_BILINEAR
                             : settings.weights == RenderSettings::Weights::Normal ? VCT_WEIGHTS_NORMAL
                                                                                   : VCT_WEIGHTS_SG;
    // The SG ratio term's power (sgRatioPower: β/2 when whole, else 0), 0 for the other weights so that β does
    // not multiply their pipelines. A live β slider lands mostly on the power-0 pipeline.
    const uint32_t ratioPower = weights == VCT_WEIGHTS_SG ? uint32_t(glsl::sgRatioPower(settings.beta)) : 0u;
    // Indexed by constant_id (VCT_SPEC_TRACE_SCALE, VCT_UPSAMPLE_SPEC_*).
    // The image size a multiple of s: no sample traced at a clamped pixel (shaders/upsample.comp, WHOLE_CELLS).
    const bool wholeCells = width % settings.traceScale == 0 && height % settings.traceScale == 0;
    const std::vector<uint32_t> constants = {settings.traceScale,          weights,
                                             settings.temporal ? 1u : 0u,  settings.writeWeightSum ? 1u : 0u,
                                             perPixel(settings) ? 1u : 0u, ratioPower,
                                             wholeCells ? 1u : 0u};
    const uint32_t key = constants[0] | constants[1] << 8 | constants[2] << 16 | constants[3] << 17 |
                         constants[4] << 18 | constants[5] << 19 | constants[6] << 27;
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
    vk::Pipeline pipeline =
        vk::Pipeline::compute(context_, name(), "upsample.comp", resources_.bindings(), 0, constants);
    return pipelines_.emplace(key, std::move(pipeline)).first->second;
}

void UpsamplePass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    // An empty resample list whose indirect dispatch is (0, 1, 1) groups; the shader counts x up. (Last
    // frame's resample pass may still read the list: use() orders the update after it.)
    const gpu::ResampleListHeader empty{{0, 0, 0, 0}, {0, 1, 1, 0}};
    t.resampleList.use(frame.cmd, vk::BufferAccess::TransferWrite);
    vkCmdUpdateBuffer(frame.cmd, t.resampleList.handle(), 0, sizeof(empty), &empty);

    const vk::Pipeline& pipeline = pipelineFor(frame.settings, t.width, t.height);
    pipeline.bind(frame.cmd);
    resources_.bind(frame, pipeline);
    // Cells from −1 (shaders/upsample.comp): per cell, a workgroup of VCT_TILE_SIZE² cells; per pixel, a workgroup
    // of VCT_TILE_SIZE² pixels, (VCT_TILE_SIZE / s)² cells.
    const uint32_t cellsX = t.indirectLow.width() + 1, cellsY = t.indirectLow.height() + 1;
    if (perPixel(frame.settings)) {
        const uint32_t groupCells = VCT_TILE_SIZE / frame.settings.traceScale;
        vkCmdDispatch(frame.cmd, (cellsX + groupCells - 1) / groupCells,
                      (cellsY + groupCells - 1) / groupCells, 1);
    } else {
        vkCmdDispatch(frame.cmd, tileCount(cellsX), tileCount(cellsY), 1);
    }
}

}  // namespace vct
