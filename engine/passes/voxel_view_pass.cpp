#include "passes/voxel_view_pass.h"

#include "core/error.h"

namespace vct {

VoxelViewPass::VoxelViewPass(const vk::Context& context, VoxelGrid& grid) : context_(context), grid_(grid) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_ = vk::Pipeline::compute(context, "voxel_view.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_VOXEL_VIEW_BINDING_VOXELS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, cs},
                                       {VCT_VOXEL_VIEW_BINDING_OUTPUT, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, cs}},
                                      sizeof(gpu::VoxelViewPushConstants));
}

void VoxelViewPass::prepare(uint32_t mip, uint32_t width, uint32_t height) {
    if (mip >= grid_.mipCount())
        throw Error("voxel view: mip " + std::to_string(mip) + " is not in 0.." + std::to_string(grid_.mipCount() - 1));
    mip_ = mip;
    if (!output_.valid() || output_.width() != width || output_.height() != height) {
        vk::ImageDesc desc;
        desc.width = width;
        desc.height = height;
        desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        output_ = vk::Image(context_, desc);
    }
}

std::vector<ImageUse> VoxelViewPass::uses(FrameTargets&) {
    return {{&grid_.radiance(), vk::ImageAccess::Sampled}, {&output_, vk::ImageAccess::StorageWrite}};
}

void VoxelViewPass::execute(const FrameContext& frame) {
    pipeline_.bind(frame.cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .sampled(VCT_VOXEL_VIEW_BINDING_VOXELS, grid_.radiance().view(), grid_.sampler())
        .storage(VCT_VOXEL_VIEW_BINDING_OUTPUT, output_.view())
        .push(frame.context, frame.cmd, pipeline_);
    gpu::VoxelViewPushConstants push{};
    push.params.x = mip_;
    pipeline_.pushConstants(frame.cmd, &push, sizeof(push));
    vkCmdDispatch(frame.cmd, tileCount(output_.width()), tileCount(output_.height()), 1);
}

}  // namespace vct
