#include "passes/voxelize_pass.h"

namespace vct {

namespace {

// Binding numbers: shaders/voxelize.comp's (the per-draw ones are written in voxelizeInstances).
constexpr uint32_t kVertices = 3, kBaseColor = 5, kEmissive = 6, kAccumulator = 7, kMetallicRoughness = 8;

// Binding numbers: shaders/voxel_resolve.comp's.
ResourceTable resolveResources(VoxelGrid& grid) {
    // Without moving instances the static accumulator stands in for the dynamic one (the shader does not read
    // it twice).
    vk::Buffer& dynamic = grid.hasMovingInstances() ? grid.dynamicAccumulator() : grid.staticAccumulator();
    // The volumes read-write rather than write: frames that skip the resolve (static scenes) keep them.
    return {"voxelize",
            {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
             {1, Resource::buffer("staticAccumulator", grid.staticAccumulator()), Access::Read},
             // Read-write: the resolve zeroes what it read of the moving instances' accumulator.
             {2, Resource::buffer("dynamicAccumulator", dynamic), Access::ReadWrite},
             {3, Resource::image("albedo", grid.albedo()), Access::ReadWrite},
             {4, Resource::image("normal", grid.normal()), Access::ReadWrite},
             {5, Resource::image("emission", grid.emission()), Access::ReadWrite},
             {VCT_BINDING_BRICKS, Resource::buffer("bricks", grid.brickTable()), Access::Read}}};
}

}  // namespace

VoxelizePass::VoxelizePass(const vk::Context& context, VoxelGrid& grid)
    : grid_(grid),
      voxelizeResources_(
          "voxelize", {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
                       {1, Resource::scene(SceneBuffer::Instances), Access::Read},
                       {2, Resource::scene(SceneBuffer::Materials), Access::Read},
                       // Read as floats: the scene's static vertices, or the skin pass's deformed ones
                       // (written per dispatch; the skin pass's barrier orders them).
                       {kVertices, Resource::perDraw("vertices", true), Access::Read},
                       {4, Resource::scene(SceneBuffer::Indices), Access::Read},
                       // The material's textures, and the accumulator of the instances being voxelized.
                       {kBaseColor, Resource::perDraw("baseColorTexture"), Access::Sampled},
                       {kEmissive, Resource::perDraw("emissiveTexture"), Access::Sampled},
                       {kAccumulator, Resource::perDraw("accumulator", true), Access::ReadWrite},
                       {kMetallicRoughness, Resource::perDraw("metallicRoughnessTexture"), Access::Sampled},
                       {VCT_BINDING_BRICKS, Resource::buffer("bricks", grid.brickTable()), Access::Read}}),
      resolveResources_(resolveResources(grid)) {
    voxelize_ = vk::Pipeline::compute(context, name(), "voxelize.comp", voxelizeResources_.bindings(),
                                      sizeof(gpu::VoxelizePushConstants));
    resolve_ = vk::Pipeline::compute(context, name(), "voxel_resolve.comp", resolveResources_.bindings(),
                                     sizeof(gpu::VoxelizePushConstants));
}

void VoxelizePass::voxelizeInstances(const FrameContext& frame, bool moving, const vk::Buffer& accumulator) {
    const GpuScene& gpuScene = frame.scene;
    const Scene& scene = gpuScene.scene();
    VkCommandBuffer cmd = frame.cmd;
    voxelize_.bind(cmd);
    int boundMaterial = -1;
    VkBuffer boundVertices = VK_NULL_HANDLE;
    const GpuDeform& deform = gpuScene.deform();
    const auto& instances = gpuScene.instances();
    for (uint32_t i = 0; i < instances.size(); ++i) {
        if (instances[i].moving != moving) continue;
        const bool deformed = deform.deformed(i);
        const VkBuffer vertices = deformed ? deform.currentBuffer() : gpuScene.vertexBuffer();
        const auto& meshPrimitives = scene.meshes[size_t(instances[i].mesh)].primitives;
        for (uint32_t k = 0; k < meshPrimitives.size(); ++k) {
            const Primitive& primitive = scene.primitives[meshPrimitives[k]];
            const uint32_t triangles = primitive.indexCount / 3;
            if (triangles == 0) continue;
            // Descriptors change only with the material (its textures) or the vertex source, as in scene_draw.cpp.
            if (int(primitive.material) != boundMaterial || vertices != boundVertices) {
                const Material& material = scene.materials[primitive.material];
                using Slot = GpuScene::Slot;
                voxelizeResources_.writer(frame)
                    .sampled(kBaseColor, gpuScene.textureView(material, Slot::BaseColor),
                             gpuScene.textureSampler(material, Slot::BaseColor))
                    .sampled(kEmissive, gpuScene.textureView(material, Slot::Emissive),
                             gpuScene.textureSampler(material, Slot::Emissive))
                    .sampled(kMetallicRoughness, gpuScene.textureView(material, Slot::MetallicRoughness),
                             gpuScene.textureSampler(material, Slot::MetallicRoughness))
                    .storageBuffer(kAccumulator, accumulator.handle())
                    .storageBuffer(kVertices, vertices)
                    .push(frame.context, cmd, voxelize_);
                boundMaterial = int(primitive.material);
                boundVertices = vertices;
            }
            gpu::VoxelizePushConstants push{};
            push.draw = glm::uvec4(i, primitive.material, primitive.firstIndex, triangles);
            const int32_t vertexOffset = deformed ? deform.deformedOffset(i, k) : primitive.vertexOffset;
            push.params = glm::uvec4(uint32_t(vertexOffset), primitive.hasColors ? 1u : 0u, 0, 0);
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
    const std::optional<VoxelGrid::UpdateRegions>& regions = grid_.updateRegions();
    // A static scene's volumes, once resolved, never change: a frame that rebuilds the grid for a changed
    // light or a camera cut re-injects, but has nothing to voxelize or resolve.
    if (!voxelizeStatic && !moving && resolved_ && !frame.settings.recomputeEveryFrame) return;
    resolved_ = true;
    if (voxelizeStatic || moving) {
        // Each accumulator is cleared (the static one then maybe filled from the cache) and accumulated into
        // by the voxelize shader's atomics: every step's barrier follows from the buffer's tracked use.
        vk::Buffer& staticAccumulator = grid_.staticAccumulator();
        vk::Buffer& dynamicAccumulator = grid_.dynamicAccumulator();
        if (voxelizeStatic) {
            staticAccumulator.use(cmd, vk::BufferAccess::TransferWrite);
            vkCmdFillBuffer(cmd, staticAccumulator.handle(), 0, VK_WHOLE_SIZE, 0);
        }
        // The moving instances' accumulator is zero wherever the last resolve read it, which covers every voxel
        // they wrote (render/voxel_update.h): cleared whole only when the whole grid is updated.
        if (moving && !regions) {
            dynamicAccumulator.use(cmd, vk::BufferAccess::TransferWrite);
            vkCmdFillBuffer(cmd, dynamicAccumulator.handle(), 0, VK_WHOLE_SIZE, 0);
        }
        if (fromCache) {
            // The cached voxels over the cleared buffer (write after write); the empty ones stay zero.
            staticAccumulator.use(cmd, vk::BufferAccess::TransferWrite);
            grid_.recordStaticCacheUpload(cmd);
        }
        constexpr vk::BufferAccess atomics = vk::BufferAccess::ShaderRead | vk::BufferAccess::ShaderWrite;
        if (voxelizeStatic) {
            staticAccumulator.use(cmd, atomics);
            if (!fromCache) voxelizeInstances(frame, false, staticAccumulator);
            grid_.markStaticVoxelized();
        }
        if (moving) {
            dynamicAccumulator.use(cmd, atomics);
            voxelizeInstances(frame, true, dynamicAccumulator);
        }
    }

    resolve_.bind(cmd);
    resolveResources_.bind(frame, resolve_);
    gpu::VoxelizePushConstants push{};
    push.params = glm::uvec4(0, moving ? 1u : 0u, moving ? 1u : 0u, 0);
    // The whole grid: every allocated brick; a region: each brick of its (brick-aligned) box.
    if (!regions) {
        resolve_.pushConstants(cmd, &push, sizeof(push));
        dispatchBricks(cmd, grid_.bricks().brickCount());
        return;
    }
    const VoxelRegion& region = regions->resolve;
    push.region = glm::uvec4(region.min, 1u);
    resolve_.pushConstants(cmd, &push, sizeof(push));
    dispatchRegionBricks(cmd, region);
}

}  // namespace vct
