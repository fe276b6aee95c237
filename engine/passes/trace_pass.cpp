#include "passes/trace_pass.h"

#include "vk/check.h"

namespace vct {

TracePass::TracePass(const vk::Context& context, uint32_t traceScale)
    : device_(context.device()), fullResolution_(traceScale <= 1) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    pipeline_ = vk::Pipeline::compute(context, "trace.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_TRACE_BINDING_DEPTH, sampled, cs},
                                       {VCT_TRACE_BINDING_NORMAL_ROUGHNESS, sampled, cs},
                                       {VCT_TRACE_BINDING_VOXELS, sampled, cs},
                                       {VCT_TRACE_BINDING_INDIRECT, storage, cs},
                                       {VCT_TRACE_BINDING_GUIDE_POSITION, storage, cs},
                                       {VCT_TRACE_BINDING_GUIDE_NORMAL, storage, cs},
                                       {VCT_TRACE_BINDING_GUIDE_AXIS, storage, cs}},
                                      0, {traceScale});  // VCT_SPEC_TRACE_SCALE

    // The stand-in grid: 2³ transparent black voxels (3D needs depth > 1), cleared once.
    vk::ImageDesc desc;
    desc.width = desc.height = desc.depth = 2;
    desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    emptyGrid_ = vk::Image(context, desc);
    context.submitAndWait([&](VkCommandBuffer cmd) {
        emptyGrid_.use(cmd, vk::ImageAccess::TransferDst);
        const VkClearColorValue zero{};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, emptyGrid_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        emptyGrid_.use(cmd, vk::ImageAccess::Sampled);
    });
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    info.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    info.maxLod = VK_LOD_CLAMP_NONE;
    VK_CHECK(vkCreateSampler(device_, &info, nullptr, &emptySampler_));
}

TracePass::~TracePass() {
    if (emptySampler_) vkDestroySampler(device_, emptySampler_, nullptr);
}

vk::Image& TracePass::output(FrameTargets& t) const { return fullResolution_ ? t.indirect : t.indirectLow; }

std::vector<ImageUse> TracePass::uses(FrameTargets& t) {
    return {{&t.depth, vk::ImageAccess::Sampled},
            {&t.normalRoughness, vk::ImageAccess::Sampled},
            {voxels().radiance, vk::ImageAccess::Sampled},
            {&output(t), vk::ImageAccess::StorageWrite},
            {&t.guidePosition, vk::ImageAccess::StorageWrite},
            {&t.guideNormal, vk::ImageAccess::StorageWrite},
            {&t.guideAxis, vk::ImageAccess::StorageWrite}};
}

void TracePass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    const Samplers& s = frame.samplers;
    const VoxelSource grid = voxels();
    pipeline_.bind(frame.cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .sampled(VCT_TRACE_BINDING_DEPTH, t.depth.view(), s.nearestClamp,
                 VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
        .sampled(VCT_TRACE_BINDING_NORMAL_ROUGHNESS, t.normalRoughness.view(), s.nearestClamp)
        .sampled(VCT_TRACE_BINDING_VOXELS, grid.radiance->view(), grid.sampler)
        .storage(VCT_TRACE_BINDING_INDIRECT, output(t).view())
        .storage(VCT_TRACE_BINDING_GUIDE_POSITION, t.guidePosition.view())
        .storage(VCT_TRACE_BINDING_GUIDE_NORMAL, t.guideNormal.view())
        .storage(VCT_TRACE_BINDING_GUIDE_AXIS, t.guideAxis.view())
        .push(frame.context, frame.cmd, pipeline_);
    vkCmdDispatch(frame.cmd, tileCount(output(t).width()), tileCount(output(t).height()), 1);
}

}  // namespace vct
