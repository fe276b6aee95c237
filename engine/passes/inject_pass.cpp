#include "passes/inject_pass.h"

namespace vct {

InjectPass::InjectPass(const vk::Context& context, VoxelGrid& grid) : grid_(grid) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType image = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    pipeline_ = vk::Pipeline::compute(context, "inject.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_INJECT_BINDING_LIGHTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
                                       {VCT_INJECT_BINDING_ALBEDO, image, cs},
                                       {VCT_INJECT_BINDING_NORMAL, image, cs},
                                       {VCT_INJECT_BINDING_EMISSION, image, cs},
                                       {VCT_INJECT_BINDING_SHADOW_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs},
                                       {VCT_INJECT_BINDING_RADIANCE, image, cs}},
                                      0);
}

std::vector<ImageUse> InjectPass::uses(FrameTargets& t) {
    return {{&grid_.albedo(), vk::ImageAccess::StorageRead},
            {&grid_.normal(), vk::ImageAccess::StorageRead},
            {&grid_.emission(), vk::ImageAccess::StorageRead},
            {&t.shadowMap, vk::ImageAccess::Sampled},
            {&grid_.radiance(), vk::ImageAccess::StorageWrite}};
}

void InjectPass::execute(const FrameContext& frame) {
    pipeline_.bind(frame.cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .storageBuffer(VCT_INJECT_BINDING_LIGHTS, frame.scene.lightBuffer())
        .storage(VCT_INJECT_BINDING_ALBEDO, grid_.albedo().view())
        .storage(VCT_INJECT_BINDING_NORMAL, grid_.normal().view())
        .storage(VCT_INJECT_BINDING_EMISSION, grid_.emission().view())
        .sampled(VCT_INJECT_BINDING_SHADOW_MAP, frame.targets.shadowMap.view(), frame.samplers.shadowCompare,
                 VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
        .storage(VCT_INJECT_BINDING_RADIANCE, grid_.radiance().mipView(0))
        .push(frame.context, frame.cmd, pipeline_);
    const uint32_t groups = (grid_.resolution() + VCT_VOXEL_TILE - 1) / VCT_VOXEL_TILE;
    vkCmdDispatch(frame.cmd, groups, groups, groups);
}

}  // namespace vct
