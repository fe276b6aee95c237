#include "passes/direct_pass.h"

namespace vct {

DirectPass::DirectPass(const vk::Context& context) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    pipeline_ = vk::Pipeline::compute(context, "direct.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_DIRECT_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
                                       {VCT_DIRECT_BINDING_DEPTH, sampled, cs},
                                       {VCT_DIRECT_BINDING_NORMAL_ROUGHNESS, sampled, cs},
                                       {VCT_DIRECT_BINDING_BASE_COLOR_METALLIC, sampled, cs},
                                       {VCT_DIRECT_BINDING_EMISSIVE_OCCLUSION, sampled, cs},
                                       {VCT_DIRECT_BINDING_SHADOW_MAP, sampled, cs},
                                       {VCT_DIRECT_BINDING_OUTPUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs}},
                                      0);
}

std::vector<ImageUse> DirectPass::uses(FrameTargets& t) {
    return {{&t.depth, vk::ImageAccess::Sampled},           {&t.normalRoughness, vk::ImageAccess::Sampled},
            {&t.baseColorMetallic, vk::ImageAccess::Sampled}, {&t.emissiveOcclusion, vk::ImageAccess::Sampled},
            {&t.shadowMap, vk::ImageAccess::Sampled},       {&t.direct, vk::ImageAccess::StorageWrite}};
}

void DirectPass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    const Samplers& s = frame.samplers;
    constexpr VkImageLayout depthRead = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    pipeline_.bind(frame.cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .storageBuffer(VCT_DIRECT_BINDING_LIGHTS, frame.scene.lightBuffer())
        .sampled(VCT_DIRECT_BINDING_DEPTH, t.depth.view(), s.nearestClamp, depthRead)
        .sampled(VCT_DIRECT_BINDING_NORMAL_ROUGHNESS, t.normalRoughness.view(), s.nearestClamp)
        .sampled(VCT_DIRECT_BINDING_BASE_COLOR_METALLIC, t.baseColorMetallic.view(), s.nearestClamp)
        .sampled(VCT_DIRECT_BINDING_EMISSIVE_OCCLUSION, t.emissiveOcclusion.view(), s.nearestClamp)
        .sampled(VCT_DIRECT_BINDING_SHADOW_MAP, t.shadowMap.view(), s.shadowCompare, depthRead)
        .storage(VCT_DIRECT_BINDING_OUTPUT, t.direct.view())
        .push(frame.context, frame.cmd, pipeline_);
    vkCmdDispatch(frame.cmd, tileCount(t.width), tileCount(t.height), 1);
}

}  // namespace vct
