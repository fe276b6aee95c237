#include "render/scene_draw.h"

namespace vct {

namespace {

// The material's textures, written per draw.
enum TextureBinding : uint32_t { kBaseColor = 3, kMetallicRoughness, kNormal, kEmissive, kOcclusion };

}  // namespace

std::vector<ResourceRow> sceneDrawRows() {
    constexpr VkShaderStageFlags vertex = VK_SHADER_STAGE_VERTEX_BIT, fragment = VK_SHADER_STAGE_FRAGMENT_BIT;
    return {
        {VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform, vertex | fragment},
        {1, Resource::scene(SceneBuffer::Instances), Access::Read, vertex},
        {2, Resource::scene(SceneBuffer::Materials), Access::Read, fragment},
        {kBaseColor, Resource::perDraw("baseColorTexture"), Access::Sampled, fragment},
        {kMetallicRoughness, Resource::perDraw("metallicRoughnessTexture"), Access::Sampled, fragment},
        {kNormal, Resource::perDraw("normalTexture"), Access::Sampled, fragment},
        {kEmissive, Resource::perDraw("emissiveTexture"), Access::Sampled, fragment},
        {kOcclusion, Resource::perDraw("occlusionTexture"), Access::Sampled, fragment},
    };
}

std::vector<DrawItem> sceneDrawItems(const GpuScene& gpuScene, DrawSet set) {
    const Scene& scene = gpuScene.scene();
    std::vector<DrawItem> items;
    const auto& instances = gpuScene.instances();
    for (uint32_t i = 0; i < instances.size(); ++i) {
        const auto& meshPrimitives = scene.meshes[size_t(instances[i].mesh)].primitives;
        for (uint32_t k = 0; k < meshPrimitives.size(); ++k) {
            const bool blended =
                scene.materials[scene.primitives[meshPrimitives[k]].material].alphaMode == AlphaMode::Blend;
            if (set == DrawSet::All || blended == (set == DrawSet::Blended)) items.push_back({i, k});
        }
    }
    return items;
}

void drawScene(const FrameContext& frame, const vk::Pipeline& pipeline, const ResourceTable& resources,
               uint32_t previousVerticesBinding, DrawSet set) {
    drawItems(frame, pipeline, resources, sceneDrawItems(frame.scene, set), previousVerticesBinding);
}

void drawItems(const FrameContext& frame, const vk::Pipeline& pipeline, const ResourceTable& resources,
               const std::vector<DrawItem>& items, uint32_t previousVerticesBinding) {
    const GpuScene& gpuScene = frame.scene;
    const Scene& scene = gpuScene.scene();
    VkCommandBuffer cmd = frame.cmd;
    pipeline.bind(cmd);
    VkDeviceSize offset = 0;
    VkBuffer vertexBuffer = gpuScene.vertexBuffer();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
    const GpuDeform& deform = gpuScene.deform();
    vkCmdBindIndexBuffer(cmd, gpuScene.indexBuffer(), 0, VK_INDEX_TYPE_UINT32);

    int boundMaterial = -1;
    const auto& instances = gpuScene.instances();
    for (const DrawItem& item : items) {
        const uint32_t i = item.instance, k = item.meshPrimitive;
        // Deformed instances from the skin pass's buffer; the static vertex buffer for everything else.
        const bool deformed = deform.deformed(i);
        const VkBuffer source = deformed ? deform.currentBuffer() : gpuScene.vertexBuffer();
        if (source != vertexBuffer) {
            vertexBuffer = source;
            vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
        }
        const auto& meshPrimitives = scene.meshes[size_t(instances[i].mesh)].primitives;
        const Primitive& primitive = scene.primitives[meshPrimitives[k]];
        const Material& material = scene.materials[primitive.material];
        // Descriptors change only with the material (textures); instances differ by push constant.
        if (int(primitive.material) != boundMaterial) {
            using Slot = GpuScene::Slot;
            auto texture = [&](Slot slot) {
                return std::make_pair(gpuScene.textureView(material, slot),
                                      gpuScene.textureSampler(material, slot));
            };
            auto [baseView, baseSampler] = texture(Slot::BaseColor);
            auto [mrView, mrSampler] = texture(Slot::MetallicRoughness);
            auto [normalView, normalSampler] = texture(Slot::Normal);
            auto [emissiveView, emissiveSampler] = texture(Slot::Emissive);
            auto [aoView, aoSampler] = texture(Slot::Occlusion);
            vk::DescriptorWriter writer = resources.writer(frame);
            if (previousVerticesBinding != kNoBinding)
                writer.storageBuffer(previousVerticesBinding, deform.previousBuffer());
            writer.sampled(kBaseColor, baseView, baseSampler)
                .sampled(kMetallicRoughness, mrView, mrSampler)
                .sampled(kNormal, normalView, normalSampler)
                .sampled(kEmissive, emissiveView, emissiveSampler)
                .sampled(kOcclusion, aoView, aoSampler)
                .push(frame.context, cmd, pipeline);
            vkCmdSetCullMode(cmd, material.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
            boundMaterial = int(primitive.material);
        }
        gpu::DrawPushConstants push{
            glm::uvec4(i, primitive.material, deformed ? 1u : 0u, primitive.hasColors ? 1u : 0u)};
        pipeline.pushConstants(cmd, &push, sizeof(push));
        const int32_t vertexOffset = deformed ? deform.deformedOffset(i, k) : primitive.vertexOffset;
        vkCmdDrawIndexed(cmd, primitive.indexCount, 1, primitive.firstIndex, vertexOffset, 0);
    }
}

void beginSceneRendering(VkCommandBuffer cmd, VkExtent2D extent,
                         const std::vector<VkRenderingAttachmentInfo>& colors,
                         const VkRenderingAttachmentInfo& depth) {
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, extent};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = uint32_t(colors.size());
    rendering.pColorAttachments = colors.data();
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &rendering);
    const VkViewport viewport{0, 0, float(extent.width), float(extent.height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace vct
