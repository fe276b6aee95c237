#include "passes/voxelize_pass.h"

#include "vk/barrier.h"

namespace vct {

namespace {

// The accumulators are plain buffers, outside the image-use tracking: global barriers order them.
using vk::memoryBarrier;

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kStorageRW = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
// Clearing the accumulators, and the copy of a voxel cache into the static one.
constexpr VkPipelineStageFlags2 kTransfer = VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT;
constexpr VkAccessFlags2 kTransferWrite = VK_ACCESS_2_TRANSFER_WRITE_BIT;

}  // namespace

VoxelizePass::VoxelizePass(const vk::Context& context, VoxelGrid& grid) : grid_(grid) {
    constexpr VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType ssbo = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    constexpr VkDescriptorType texture = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr VkDescriptorType image = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    voxelize_ = vk::Pipeline::compute(context, "voxelize.comp",
                                      {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                       {VCT_VOXELIZE_BINDING_INSTANCES, ssbo, cs},
                                       {VCT_VOXELIZE_BINDING_MATERIALS, ssbo, cs},
                                       {VCT_VOXELIZE_BINDING_VERTICES, ssbo, cs},
                                       {VCT_VOXELIZE_BINDING_INDICES, ssbo, cs},
                                       {VCT_VOXELIZE_BINDING_BASE_COLOR, texture, cs},
                                       {VCT_VOXELIZE_BINDING_EMISSIVE, texture, cs},
                                       {VCT_VOXELIZE_BINDING_ACCUM, ssbo, cs}},
                                      sizeof(gpu::VoxelizePushConstants));
    resolve_ = vk::Pipeline::compute(context, "voxel_resolve.comp",
                                     {{VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
                                      {VCT_RESOLVE_BINDING_STATIC, ssbo, cs},
                                      {VCT_RESOLVE_BINDING_DYNAMIC, ssbo, cs},
                                      {VCT_RESOLVE_BINDING_ALBEDO, image, cs},
                                      {VCT_RESOLVE_BINDING_NORMAL, image, cs},
                                      {VCT_RESOLVE_BINDING_EMISSION, image, cs}},
                                     sizeof(gpu::VoxelizePushConstants));
}

// Read-write rather than write: frames that skip the resolve (static scenes) must keep the contents.
std::vector<ImageUse> VoxelizePass::uses(FrameTargets&) {
    return {{&grid_.albedo(), vk::ImageAccess::StorageReadWrite},
            {&grid_.normal(), vk::ImageAccess::StorageReadWrite},
            {&grid_.emission(), vk::ImageAccess::StorageReadWrite}};
}

void VoxelizePass::voxelizeInstances(const FrameContext& frame, bool moving, VkBuffer accumulator) {
    const GpuScene& gpuScene = frame.scene;
    const Scene& scene = gpuScene.scene();
    VkCommandBuffer cmd = frame.cmd;
    voxelize_.bind(cmd);
    int boundMaterial = -1;
    const auto& instances = gpuScene.instances();
    for (uint32_t i = 0; i < instances.size(); ++i) {
        if (instances[i].moving != moving) continue;
        for (uint32_t primitiveIndex : scene.meshes[size_t(instances[i].mesh)].primitives) {
            const Primitive& primitive = scene.primitives[primitiveIndex];
            const uint32_t triangles = primitive.indexCount / 3;
            if (triangles == 0) continue;
            // Descriptors change only with the material (its textures), as in scene_draw.cpp.
            if (int(primitive.material) != boundMaterial) {
                const Material& material = scene.materials[primitive.material];
                using Slot = GpuScene::Slot;
                vk::DescriptorWriter()
                    .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
                    .storageBuffer(VCT_VOXELIZE_BINDING_INSTANCES, gpuScene.instanceBuffer())
                    .storageBuffer(VCT_VOXELIZE_BINDING_MATERIALS, gpuScene.materialBuffer())
                    .storageBuffer(VCT_VOXELIZE_BINDING_VERTICES, gpuScene.vertexBuffer())
                    .storageBuffer(VCT_VOXELIZE_BINDING_INDICES, gpuScene.indexBuffer())
                    .sampled(VCT_VOXELIZE_BINDING_BASE_COLOR, gpuScene.textureView(material, Slot::BaseColor),
                             gpuScene.textureSampler(material, Slot::BaseColor))
                    .sampled(VCT_VOXELIZE_BINDING_EMISSIVE, gpuScene.textureView(material, Slot::Emissive),
                             gpuScene.textureSampler(material, Slot::Emissive))
                    .storageBuffer(VCT_VOXELIZE_BINDING_ACCUM, accumulator)
                    .push(frame.context, cmd, voxelize_);
                boundMaterial = int(primitive.material);
            }
            gpu::VoxelizePushConstants push{};
            push.draw = glm::uvec4(i, primitive.material, primitive.firstIndex, triangles);
            push.params = glm::uvec4(uint32_t(primitive.vertexOffset), 0, 0, 0);
            voxelize_.pushConstants(cmd, &push, sizeof(push));
            vkCmdDispatch(cmd, (triangles + VCT_VOXEL_GROUP_SIZE - 1) / VCT_VOXEL_GROUP_SIZE, 1, 1);
        }
    }
}

void VoxelizePass::execute(const FrameContext& frame) {
    VkCommandBuffer cmd = frame.cmd;
    const bool voxelizeStatic = !grid_.staticVoxelized();
    // A voxel cache (--voxel-cache) stands in for voxelizing the static instances: its upload is recorded
    // here, in the first frame, in this pass's timer scope. The renderer frees its staging buffer once that
    // frame is done.
    const bool fromCache = voxelizeStatic && grid_.hasStaticCache();
    const bool moving = grid_.hasMovingInstances();
    // A static scene's volumes, once resolved, never change: a frame that rebuilds the grid for a changed
    // light or a camera cut re-injects, but has nothing to voxelize or resolve.
    if (!voxelizeStatic && !moving && resolved_ && !frame.settings.recomputeEveryFrame) return;
    resolved_ = true;
    if (voxelizeStatic || moving) {
        // The last frame's resolve may still read the accumulator being cleared.
        memoryBarrier(cmd, kCompute, kStorageRW, kTransfer, kTransferWrite);
        if (voxelizeStatic) vkCmdFillBuffer(cmd, grid_.staticAccumulator(), 0, VK_WHOLE_SIZE, 0);
        if (moving) vkCmdFillBuffer(cmd, grid_.dynamicAccumulator(), 0, VK_WHOLE_SIZE, 0);
        if (fromCache) {
            // The cached voxels over the cleared buffer (write after write); the empty ones stay zero.
            memoryBarrier(cmd, kTransfer, kTransferWrite, kTransfer, kTransferWrite);
            grid_.recordStaticCacheUpload(cmd);
        }
        memoryBarrier(cmd, kTransfer, kTransferWrite, kCompute, kStorageRW);
        if (voxelizeStatic) {
            if (!fromCache) voxelizeInstances(frame, false, grid_.staticAccumulator());
            grid_.markStaticVoxelized();
        }
        if (moving) voxelizeInstances(frame, true, grid_.dynamicAccumulator());
        memoryBarrier(cmd, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kCompute, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    }

    resolve_.bind(cmd);
    vk::DescriptorWriter()
        .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
        .storageBuffer(VCT_RESOLVE_BINDING_STATIC, grid_.staticAccumulator())
        // Without moving instances the static buffer stands in (the shader does not read it twice).
        .storageBuffer(VCT_RESOLVE_BINDING_DYNAMIC, moving ? grid_.dynamicAccumulator() : grid_.staticAccumulator())
        .storage(VCT_RESOLVE_BINDING_ALBEDO, grid_.albedo().view())
        .storage(VCT_RESOLVE_BINDING_NORMAL, grid_.normal().view())
        .storage(VCT_RESOLVE_BINDING_EMISSION, grid_.emission().view())
        .push(frame.context, cmd, resolve_);
    gpu::VoxelizePushConstants push{};
    push.params = glm::uvec4(0, moving ? 1u : 0u, 0, 0);
    resolve_.pushConstants(cmd, &push, sizeof(push));
    const uint32_t groups = (grid_.resolution() + VCT_VOXEL_TILE - 1) / VCT_VOXEL_TILE;
    vkCmdDispatch(cmd, groups, groups, groups);
}

}  // namespace vct
