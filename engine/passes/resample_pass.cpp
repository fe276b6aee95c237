#include "passes/resample_pass.h"

#include "vk/barrier.h"

namespace vct {

ResamplePass::ResamplePass(const vk::Context& context, const VoxelSource& voxels) : voxels_(voxels) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    pipeline_ = vk::Pipeline::compute(context, "resample.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_TRACE_BINDING_DEPTH, sampled, cs},
                                       {VCT_TRACE_BINDING_NORMAL_ROUGHNESS, sampled, cs},
                                       {VCT_TRACE_BINDING_VOXELS, sampled, cs},
                                       {VCT_RESAMPLE_BINDING_INDIRECT, storage, cs},
                                       {VCT_RESAMPLE_BINDING_LIST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs}},
                                      0);
}

std::vector<ImageUse> ResamplePass::uses(FrameTargets& t) {
    // Read-write: only the listed pixels are written, the rest of the upsampled result must survive.
    return {{&t.depth, vk::ImageAccess::Sampled},
            {&t.normalRoughness, vk::ImageAccess::Sampled},
            {voxels_.radiance, vk::ImageAccess::Sampled},
            {&t.indirect, vk::ImageAccess::StorageReadWrite}};
}

void ResamplePass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    pipeline_.bind(frame.cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .sampled(VCT_TRACE_BINDING_DEPTH, t.depth.view(), frame.samplers.nearestClamp,
                 VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)
        .sampled(VCT_TRACE_BINDING_NORMAL_ROUGHNESS, t.normalRoughness.view(), frame.samplers.nearestClamp)
        .sampled(VCT_TRACE_BINDING_VOXELS, voxels_.radiance->view(), voxels_.sampler)
        .storage(VCT_RESAMPLE_BINDING_INDIRECT, t.indirect.view())
        .storageBuffer(VCT_RESAMPLE_BINDING_LIST, t.resampleList.handle())
        .push(frame.context, frame.cmd, pipeline_);
    vkCmdDispatchIndirect(frame.cmd, t.resampleList.handle(), offsetof(gpu::ResampleListHeader, dispatch));

    // The entry count, for the host's `resampled_fraction` (read after the frame's fence).
    VkBufferCopy region{offsetof(gpu::ResampleListHeader, counts), 0, sizeof(uint32_t)};
    vkCmdCopyBuffer(frame.cmd, t.resampleList.handle(), t.resampleCount.handle(), 1, &region);
    vk::memoryBarrier(frame.cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

}  // namespace vct
