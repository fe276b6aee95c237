#include "render/scene_draw.h"

#include <algorithm>

namespace vct {

namespace {

// The material's textures, written per draw.
enum TextureBinding : uint32_t { kBaseColor = 3, kMetallicRoughness, kNormal, kEmissive, kOcclusion };

}  // namespace

bool inDrawSet(const Material& material, DrawSet set) {
    return set == DrawSet::All || (material.alphaMode == AlphaMode::Blend) == (set == DrawSet::Blended);
}

MaterialPipelines::MaterialPipelines(const vk::Context& context, vk::Pipeline::GraphicsDesc desc,
                                     const Scene& scene, DrawSet set, bool textureLod0) {
    const bool perSlotSet = context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    std::vector<uint32_t> slotSets;  // the pipelines' VCT_SPEC_TEXTURED_SLOTS, in the order made
    for (const Material& material : scene.materials) {
        // A material the pass never draws shares the first pipeline.
        if (!inDrawSet(material, set)) {
            pipelineOfMaterial_.push_back(0);
            continue;
        }
        const uint32_t slots = perSlotSet ? GpuScene::texturedSlots(material) : VCT_EVERY_TEXTURE_SLOT;
        auto found = std::find(slotSets.begin(), slotSets.end(), slots);
        if (found == slotSets.end()) found = slotSets.insert(slotSets.end(), slots);
        pipelineOfMaterial_.push_back(uint32_t(found - slotSets.begin()));
    }
    if (slotSets.empty()) slotSets.push_back(VCT_EVERY_TEXTURE_SLOT);  // nothing drawn: one pipeline to bind
    desc.specialization.resize(std::max<size_t>(desc.specialization.size(),
                                                std::max(VCT_SPEC_TEXTURED_SLOTS, VCT_SPEC_TEXTURE_LOD0) + 1),
                               0u);
    desc.specialization[VCT_SPEC_TEXTURE_LOD0] = textureLod0 ? 1u : 0u;
    for (uint32_t slots : slotSets) {
        desc.specialization[VCT_SPEC_TEXTURED_SLOTS] = slots;
        pipelines_.push_back(vk::Pipeline::graphics(context, desc));
    }
}

const vk::Pipeline& MaterialPipelines::forMaterial(uint32_t material) const {
    return pipelines_[material < pipelineOfMaterial_.size() ? pipelineOfMaterial_[material] : 0];
}

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
            if (inDrawSet(scene.materials[scene.primitives[meshPrimitives[k]].material], set))
                items.push_back({i, k});
        }
    }
    return items;
}

void drawScene(const FrameContext& frame, const vk::Pipeline& pipeline, const ResourceTable& resources,
               uint32_t previousVerticesBinding, DrawSet set) {
    drawItems(frame, pipeline, resources, sceneDrawItems(frame.scene, set), previousVerticesBinding);
}

void drawScene(const FrameContext& frame, const MaterialPipelines& pipelines, const ResourceTable& resources,
               uint32_t previousVerticesBinding, DrawSet set) {
    drawItems(frame, pipelines, resources, sceneDrawItems(frame.scene, set), previousVerticesBinding);
}

namespace {

// `pipelineFor(material)`: the pipeline a draw of that material uses.
template <typename PipelineFor>
void drawItemsWith(const FrameContext& frame, const PipelineFor& pipelineFor, const ResourceTable& resources,
                   const std::vector<DrawItem>& items, uint32_t previousVerticesBinding) {
    const GpuScene& gpuScene = frame.scene;
    const Scene& scene = gpuScene.scene();
    VkCommandBuffer cmd = frame.cmd;
    const vk::Pipeline* bound = nullptr;
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
        // Descriptors (and the pipeline) change only with the material; instances differ by push constant.
        if (int(primitive.material) != boundMaterial) {
            const vk::Pipeline& pipeline = pipelineFor(primitive.material);
            if (&pipeline != bound) {
                pipeline.bind(cmd);
                bound = &pipeline;
            }
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
                .push(frame.context, cmd, *bound);
            vkCmdSetCullMode(cmd, material.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
            boundMaterial = int(primitive.material);
        }
        gpu::DrawPushConstants push{
            glm::uvec4(i, primitive.material, deformed ? 1u : 0u, primitive.hasColors ? 1u : 0u)};
        bound->pushConstants(cmd, &push, sizeof(push));
        const int32_t vertexOffset = deformed ? deform.deformedOffset(i, k) : primitive.vertexOffset;
        vkCmdDrawIndexed(cmd, primitive.indexCount, 1, primitive.firstIndex, vertexOffset, 0);
    }
}

}  // namespace

void drawItems(const FrameContext& frame, const vk::Pipeline& pipeline, const ResourceTable& resources,
               const std::vector<DrawItem>& items, uint32_t previousVerticesBinding) {
    drawItemsWith(
        frame, [&](uint32_t) -> const vk::Pipeline& { return pipeline; }, resources, items,
        previousVerticesBinding);
}

void drawItems(const FrameContext& frame, const MaterialPipelines& pipelines, const ResourceTable& resources,
               const std::vector<DrawItem>& items, uint32_t previousVerticesBinding) {
    drawItemsWith(
        frame, [&](uint32_t material) -> const vk::Pipeline& { return pipelines.forMaterial(material); },
        resources, items, previousVerticesBinding);
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
