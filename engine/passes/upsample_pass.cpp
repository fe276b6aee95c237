#include "passes/upsample_pass.h"

#include "vk/barrier.h"

namespace vct {

UpsamplePass::UpsamplePass(const vk::Context& context) : context_(context) {}

const vk::Pipeline& UpsamplePass::pipelineFor(const RenderSettings& settings) {
    const uint32_t weights = settings.weights == RenderSettings::Weights::Bilinear ? VCT_WEIGHTS_BILINEAR
                             : settings.weights == RenderSettings::Weights::Normal ? VCT_WEIGHTS_NORMAL
                                                                                     : VCT_WEIGHTS_SG;
    // Indexed by constant_id (VCT_SPEC_TRACE_SCALE, VCT_UPSAMPLE_SPEC_*).
    const std::vector<uint32_t> constants = {settings.traceScale, weights, settings.temporal ? 1u : 0u,
                                             settings.writeWeightSum ? 1u : 0u};
    const uint32_t key = constants[0] | constants[1] << 8 | constants[2] << 16 | constants[3] << 17;
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    vk::Pipeline pipeline = vk::Pipeline::compute(
        context_, "upsample.comp",
        {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
         {VCT_UPSAMPLE_BINDING_INDIRECT_LOW, sampled, cs},
         {VCT_UPSAMPLE_BINDING_INDIRECT, storage, cs},
         {VCT_UPSAMPLE_BINDING_DEPTH, sampled, cs},
         {VCT_UPSAMPLE_BINDING_NORMAL_ROUGHNESS, sampled, cs},
         {VCT_UPSAMPLE_BINDING_MOTION, sampled, cs},
         {VCT_UPSAMPLE_BINDING_PREV_DEPTH, sampled, cs},
         {VCT_UPSAMPLE_BINDING_PREV_NORMAL_ROUGHNESS, sampled, cs},
         {VCT_UPSAMPLE_BINDING_INDIRECT_HISTORY, sampled, cs},
         {VCT_UPSAMPLE_BINDING_WEIGHT_SUM, storage, cs},
         {VCT_UPSAMPLE_BINDING_RESAMPLE_LIST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
         {VCT_UPSAMPLE_BINDING_GUIDE_POSITION, sampled, cs},
         {VCT_UPSAMPLE_BINDING_GUIDE_NORMAL, sampled, cs},
         {VCT_UPSAMPLE_BINDING_GUIDE_AXIS, sampled, cs}},
        0, constants);
    return pipelines_.emplace(key, std::move(pipeline)).first->second;
}

std::vector<ImageUse> UpsamplePass::uses(FrameTargets& t) {
    return {{&t.indirectLow, vk::ImageAccess::Sampled},
            {&t.guidePosition, vk::ImageAccess::Sampled},
            {&t.guideNormal, vk::ImageAccess::Sampled},
            {&t.guideAxis, vk::ImageAccess::Sampled},
            {&t.depth, vk::ImageAccess::Sampled},
            {&t.normalRoughness, vk::ImageAccess::Sampled},
            {&t.motion, vk::ImageAccess::Sampled},
            {&t.prevDepth, vk::ImageAccess::Sampled},
            {&t.prevNormalRoughness, vk::ImageAccess::Sampled},
            {&t.indirectHistory, vk::ImageAccess::Sampled},
            {&t.indirect, vk::ImageAccess::StorageWrite},
            {&t.weightSum, vk::ImageAccess::StorageWrite}};
}

void UpsamplePass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    const Samplers& s = frame.samplers;
    // An empty resample list whose indirect dispatch is (0, 1, 1) groups; the shader counts x up.
    const gpu::ResampleListHeader empty{{0, 0, 0, 0}, {0, 1, 1, 0}};
    vk::memoryBarrier(frame.cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT |
                                     VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdUpdateBuffer(frame.cmd, t.resampleList.handle(), 0, sizeof(empty), &empty);
    vk::memoryBarrier(frame.cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

    const vk::Pipeline& pipeline = pipelineFor(frame.settings);
    pipeline.bind(frame.cmd);
    constexpr VkImageLayout depthRead = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .sampled(VCT_UPSAMPLE_BINDING_INDIRECT_LOW, t.indirectLow.view(), s.nearestClamp)
        .sampled(VCT_UPSAMPLE_BINDING_GUIDE_POSITION, t.guidePosition.view(), s.nearestClamp)
        .sampled(VCT_UPSAMPLE_BINDING_GUIDE_NORMAL, t.guideNormal.view(), s.nearestClamp)
        .sampled(VCT_UPSAMPLE_BINDING_GUIDE_AXIS, t.guideAxis.view(), s.nearestClamp)
        .sampled(VCT_UPSAMPLE_BINDING_DEPTH, t.depth.view(), s.nearestClamp, depthRead)
        .sampled(VCT_UPSAMPLE_BINDING_NORMAL_ROUGHNESS, t.normalRoughness.view(), s.nearestClamp)
        .sampled(VCT_UPSAMPLE_BINDING_MOTION, t.motion.view(), s.nearestClamp)
        .sampled(VCT_UPSAMPLE_BINDING_PREV_DEPTH, t.prevDepth.view(), s.nearestClamp, depthRead)
        .sampled(VCT_UPSAMPLE_BINDING_PREV_NORMAL_ROUGHNESS, t.prevNormalRoughness.view(), s.nearestClamp)
        .sampled(VCT_UPSAMPLE_BINDING_INDIRECT_HISTORY, t.indirectHistory.view(), s.nearestClamp)
        .storage(VCT_UPSAMPLE_BINDING_INDIRECT, t.indirect.view())
        .storage(VCT_UPSAMPLE_BINDING_WEIGHT_SUM, t.weightSum.view())
        .storageBuffer(VCT_UPSAMPLE_BINDING_RESAMPLE_LIST, t.resampleList.handle())
        .push(frame.context, frame.cmd, pipeline);
    // One invocation per low-res cell of s×s pixels, from cell −1 (shaders/upsample.comp).
    vkCmdDispatch(frame.cmd, tileCount(t.indirectLow.width() + 1), tileCount(t.indirectLow.height() + 1),
                  1);
    // The list feeds the resample pass's indirect dispatch and its shader, and the count's copy to the host.
    vk::memoryBarrier(frame.cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                          VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                          VK_ACCESS_2_TRANSFER_READ_BIT);
}

}  // namespace vct
