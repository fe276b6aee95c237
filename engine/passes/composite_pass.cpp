#include "passes/composite_pass.h"

namespace vct {

CompositePass::CompositePass(const vk::Context& context) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_ = vk::Pipeline::compute(context, "composite.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_COMPOSITE_BINDING_DIRECT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs},
                                       {VCT_COMPOSITE_BINDING_HDR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs},
                                       {VCT_COMPOSITE_BINDING_LDR, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs}},
                                      0);
}

std::vector<ImageUse> CompositePass::uses(FrameTargets& t) {
    return {{&t.direct, vk::ImageAccess::StorageRead},
            {&t.hdr, vk::ImageAccess::StorageWrite},
            {&t.ldr, vk::ImageAccess::StorageWrite}};
}

void CompositePass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    pipeline_.bind(frame.cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .storage(VCT_COMPOSITE_BINDING_DIRECT, t.direct.view())
        .storage(VCT_COMPOSITE_BINDING_HDR, t.hdr.view())
        .storage(VCT_COMPOSITE_BINDING_LDR, t.ldr.view())
        .push(frame.context, frame.cmd, pipeline_);
    vkCmdDispatch(frame.cmd, tileCount(t.width), tileCount(t.height), 1);
}

}  // namespace vct
