#include "passes/upsample_pass.h"

namespace vct {

UpsamplePass::UpsamplePass(const vk::Context& context) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    pipeline_ = vk::Pipeline::compute(context, "upsample.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_UPSAMPLE_BINDING_DIFFUSE_LOW, sampled, cs},
                                       {VCT_UPSAMPLE_BINDING_SPECULAR_LOW, sampled, cs},
                                       {VCT_UPSAMPLE_BINDING_DIFFUSE, storage, cs},
                                       {VCT_UPSAMPLE_BINDING_SPECULAR, storage, cs}},
                                      0);
}

std::vector<ImageUse> UpsamplePass::uses(FrameTargets& t) {
    return {{&t.diffuseIndirectLow, vk::ImageAccess::Sampled},
            {&t.specularIndirectLow, vk::ImageAccess::Sampled},
            {&t.diffuseIndirect, vk::ImageAccess::StorageWrite},
            {&t.specularIndirect, vk::ImageAccess::StorageWrite}};
}

void UpsamplePass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    pipeline_.bind(frame.cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .sampled(VCT_UPSAMPLE_BINDING_DIFFUSE_LOW, t.diffuseIndirectLow.view(), frame.samplers.linearClamp)
        .sampled(VCT_UPSAMPLE_BINDING_SPECULAR_LOW, t.specularIndirectLow.view(), frame.samplers.linearClamp)
        .storage(VCT_UPSAMPLE_BINDING_DIFFUSE, t.diffuseIndirect.view())
        .storage(VCT_UPSAMPLE_BINDING_SPECULAR, t.specularIndirect.view())
        .push(frame.context, frame.cmd, pipeline_);
    vkCmdDispatch(frame.cmd, tileCount(t.width), tileCount(t.height), 1);
}

}  // namespace vct
