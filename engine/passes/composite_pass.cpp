#include "passes/composite_pass.h"

namespace vct {

CompositePass::CompositePass(const vk::Context& context) : dfg_(context) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    pipeline_ = vk::Pipeline::compute(context, "composite.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_COMPOSITE_BINDING_DIRECT, storage, cs},
                                       {VCT_COMPOSITE_BINDING_HDR, storage, cs},
                                       {VCT_COMPOSITE_BINDING_LDR, storage, cs},
                                       {VCT_COMPOSITE_BINDING_DEPTH, sampled, cs},
                                       {VCT_COMPOSITE_BINDING_NORMAL_ROUGHNESS, sampled, cs},
                                       {VCT_COMPOSITE_BINDING_BASE_COLOR_METALLIC, sampled, cs},
                                       {VCT_COMPOSITE_BINDING_EMISSIVE_OCCLUSION, sampled, cs},
                                       {VCT_COMPOSITE_BINDING_INDIRECT, storage, cs},
                                       {VCT_COMPOSITE_BINDING_DFG, sampled, cs}},
                                      0);
}

std::vector<ImageUse> CompositePass::uses(FrameTargets& t) {
    std::vector<ImageUse> uses = {
        {&t.direct, vk::ImageAccess::StorageRead},        {&t.depth, vk::ImageAccess::Sampled},
        {&t.normalRoughness, vk::ImageAccess::Sampled},   {&t.baseColorMetallic, vk::ImageAccess::Sampled},
        {&t.emissiveOcclusion, vk::ImageAccess::Sampled}, {&t.indirect, vk::ImageAccess::StorageRead},
        {&t.hdr, vk::ImageAccess::StorageWrite},          {&t.ldr, vk::ImageAccess::StorageWrite}};
    return uses;
}

void CompositePass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    const Samplers& s = frame.samplers;
    pipeline_.bind(frame.cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .storage(VCT_COMPOSITE_BINDING_DIRECT, t.direct.view())
        .storage(VCT_COMPOSITE_BINDING_HDR, t.hdr.view())
        .storage(VCT_COMPOSITE_BINDING_LDR, t.ldr.view())
        .sampled(VCT_COMPOSITE_BINDING_DEPTH, t.depth.view(), s.nearestClamp,
                 VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
        .sampled(VCT_COMPOSITE_BINDING_NORMAL_ROUGHNESS, t.normalRoughness.view(), s.nearestClamp)
        .sampled(VCT_COMPOSITE_BINDING_BASE_COLOR_METALLIC, t.baseColorMetallic.view(), s.nearestClamp)
        .sampled(VCT_COMPOSITE_BINDING_EMISSIVE_OCCLUSION, t.emissiveOcclusion.view(), s.nearestClamp)
        .storage(VCT_COMPOSITE_BINDING_INDIRECT, t.indirect.view())
        .sampled(VCT_COMPOSITE_BINDING_DFG, dfg_.image().view(), dfg_.sampler())
        .push(frame.context, frame.cmd, pipeline_);
    vkCmdDispatch(frame.cmd, tileCount(t.width), tileCount(t.height), 1);
}

}  // namespace vct
