#include "render/scene_draw.h"

namespace vct {

std::vector<vk::Binding> sceneDrawBindings() {
    constexpr VkShaderStageFlags both = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    constexpr VkDescriptorType texture = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    return {
        {VCT_BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, both},
        {VCT_DRAW_BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT},
        {VCT_DRAW_BINDING_MATERIALS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT},
        {VCT_DRAW_BINDING_BASE_COLOR, texture, VK_SHADER_STAGE_FRAGMENT_BIT},
        {VCT_DRAW_BINDING_METALLIC_ROUGHNESS, texture, VK_SHADER_STAGE_FRAGMENT_BIT},
        {VCT_DRAW_BINDING_NORMAL, texture, VK_SHADER_STAGE_FRAGMENT_BIT},
        {VCT_DRAW_BINDING_EMISSIVE, texture, VK_SHADER_STAGE_FRAGMENT_BIT},
        {VCT_DRAW_BINDING_OCCLUSION, texture, VK_SHADER_STAGE_FRAGMENT_BIT},
    };
}

void drawScene(const FrameContext& frame, const vk::Pipeline& pipeline) {
    const GpuScene& gpuScene = frame.scene;
    const Scene& scene = gpuScene.scene();
    VkCommandBuffer cmd = frame.cmd;
    pipeline.bind(cmd);
    VkDeviceSize offset = 0;
    VkBuffer vertexBuffer = gpuScene.vertexBuffer();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
    vkCmdBindIndexBuffer(cmd, gpuScene.indexBuffer(), 0, VK_INDEX_TYPE_UINT32);

    int boundMaterial = -1;
    const auto& instances = gpuScene.instances();
    for (uint32_t i = 0; i < instances.size(); ++i) {
        for (uint32_t primitiveIndex : scene.meshes[size_t(instances[i].mesh)].primitives) {
            const Primitive& primitive = scene.primitives[primitiveIndex];
            const Material& material = scene.materials[primitive.material];
            // Descriptors change only with the material (textures); instances differ by push constant.
            if (int(primitive.material) != boundMaterial) {
                using Slot = GpuScene::Slot;
                auto texture = [&](Slot slot) {
                    return std::make_pair(gpuScene.textureView(material, slot), gpuScene.textureSampler(material, slot));
                };
                auto [baseView, baseSampler] = texture(Slot::BaseColor);
                auto [mrView, mrSampler] = texture(Slot::MetallicRoughness);
                auto [normalView, normalSampler] = texture(Slot::Normal);
                auto [emissiveView, emissiveSampler] = texture(Slot::Emissive);
                auto [aoView, aoSampler] = texture(Slot::Occlusion);
                vk::DescriptorWriter()
                    .uniform(VCT_BINDING_FRAME, frame.frameUniforms)
                    .storageBuffer(VCT_DRAW_BINDING_INSTANCES, gpuScene.instanceBuffer())
                    .storageBuffer(VCT_DRAW_BINDING_MATERIALS, gpuScene.materialBuffer())
                    .sampled(VCT_DRAW_BINDING_BASE_COLOR, baseView, baseSampler)
                    .sampled(VCT_DRAW_BINDING_METALLIC_ROUGHNESS, mrView, mrSampler)
                    .sampled(VCT_DRAW_BINDING_NORMAL, normalView, normalSampler)
                    .sampled(VCT_DRAW_BINDING_EMISSIVE, emissiveView, emissiveSampler)
                    .sampled(VCT_DRAW_BINDING_OCCLUSION, aoView, aoSampler)
                    .push(frame.context, cmd, pipeline);
                vkCmdSetCullMode(cmd, material.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
                boundMaterial = int(primitive.material);
            }
            gpu::DrawPushConstants push{glm::uvec4(i, primitive.material, 0, 0)};
            pipeline.pushConstants(cmd, &push, sizeof(push));
            vkCmdDrawIndexed(cmd, primitive.indexCount, 1, primitive.firstIndex, primitive.vertexOffset, 0);
        }
    }
}

}  // namespace vct
