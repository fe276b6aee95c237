#include "passes/skin_pass.h"

namespace vct {

namespace {

// Binding numbers: shaders/skin.comp's.
ResourceTable skinResources(GpuDeform& deform) {
    return {"skin",
            {{0, Resource::scene(SceneBuffer::Vertices), Access::Read},  // the rest vertices, as floats
             {1, Resource::buffer("skinVertices", deform.skinVertices()), Access::Read},
             {2, Resource::buffer("morphDeltas", deform.morphDeltas()), Access::Read},
             {3, Resource::buffer("jointMatrices", deform.jointMatrices()), Access::Read},
             {4, Resource::buffer("morphWeights", deform.morphWeights()), Access::Read},
             {5, Resource::buffer("deformed", deform.current()), Access::Write},
             {6, Resource::buffer("previousDeformed", deform.previous()), Access::Write}}};
}

}  // namespace

SkinPass::SkinPass(const vk::Context& context, GpuDeform& deform)
    : deform_(deform), resources_(skinResources(deform)) {
    pipeline_ = vk::Pipeline::compute(context, name(), "skin.comp", resources_.bindings(),
                                      sizeof(gpu::SkinPushConstants));
}

void SkinPass::execute(const FrameContext& frame) {
    if (!deform_.needsWork()) return;  // the deformed buffers already hold this pose twice
    VkCommandBuffer cmd = frame.cmd;
    const bool cut = deform_.cut();
    if (!cut) {
        // Last frame's deformed vertices become the previous ones (a cut writes both instead).
        deform_.current().use(cmd, vk::BufferAccess::TransferRead);
        deform_.previous().use(cmd, vk::BufferAccess::TransferWrite);
        const VkBufferCopy region{0, 0, deform_.current().size()};
        vkCmdCopyBuffer(cmd, deform_.current().handle(), deform_.previous().handle(), 1, &region);
    }
    pipeline_.bind(cmd);
    resources_.bind(frame, pipeline_);
    for (const GpuDeform::Job& job : deform_.jobs()) {
        gpu::SkinPushConstants push = job.push;
        push.flags.x = cut ? 1u : 0u;
        pipeline_.pushConstants(cmd, &push, sizeof(push));
        vkCmdDispatch(cmd, (push.vertices.y + VCT_SKIN_GROUP_SIZE - 1) / VCT_SKIN_GROUP_SIZE, 1, 1);
    }
    // The draws read both buffers as vertex input (current) and in the vertex shader (previous, the motion),
    // the voxelization in compute: stages the buffers' tracked uses (compute and transfer only) do not name.
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    barrier.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
    barrier.dstStageMask = VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT |
                           VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    barrier.dstAccessMask = VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

}  // namespace vct
