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

void drawScene(const FrameContext& frame, const vk::Pipeline& pipeline, const ResourceTable& resources) {
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
                    return std::make_pair(gpuScene.textureView(material, slot),
                                          gpuScene.textureSampler(material, slot));
                };
                auto [baseView, baseSampler] = texture(Slot::BaseColor);
                auto [mrView, mrSampler] = texture(Slot::MetallicRoughness);
                auto [normalView, normalSampler] = texture(Slot::Normal);
                auto [emissiveView, emissiveSampler] = texture(Slot::Emissive);
                auto [aoView, aoSampler] = texture(Slot::Occlusion);
                resources.writer(frame)
                    .sampled(kBaseColor, baseView, baseSampler)
                    .sampled(kMetallicRoughness, mrView, mrSampler)
                    .sampled(kNormal, normalView, normalSampler)
                    .sampled(kEmissive, emissiveView, emissiveSampler)
                    .sampled(kOcclusion, aoView, aoSampler)
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
