#include "passes/shadow_pass.h"

#include "render/scene_draw.h"

namespace vct {

namespace {

ResourceTable shadowResources() {
    std::vector<ResourceRow> rows = sceneDrawRows();
    rows.push_back({kNoBinding, Target::shadowMap, Access::DepthAttachment});
    return {"shadow", std::move(rows)};
}

}  // namespace

ShadowPass::ShadowPass(const vk::Context& context) : resources_(shadowResources()) {
    vk::Pipeline::GraphicsDesc desc;
    desc.owner = name();
    desc.vertexShader = "shadow.vert";
    desc.depthFormat = resources_.depthFormat();
    desc.bindings = resources_.bindings();
    desc.pushConstantSize = sizeof(gpu::DrawPushConstants);
    desc.depthBias = true;
    desc.positionOnly = true;
    pipeline_ = vk::Pipeline::graphics(context, desc);
}

std::optional<TexelRect> ShadowPass::updateRect(const FrameContext& frame, const vk::Image& shadowMap) const {
    const GpuScene& scene = frame.scene;
    const bool sameDrawing =
        drawnImage_ == shadowMap.handle() && drawnLight_ == scene.shadowLightIndex() &&
        drawnLightViewProj_ == scene.lightViewProj() &&
        drawnBiases_ == glm::vec2(frame.settings.shadowDepthBias, frame.settings.shadowSlopeBias);
    if (!sameDrawing || frame.settings.recomputeEveryFrame || !scene.onlyInstancesMovedInLastUpdate())
        return std::nullopt;
    return movedRect(scene.lightViewProj(), scene.movedBounds(), {shadowMap.width(), shadowMap.height()});
}

void ShadowPass::execute(const FrameContext& frame) {
    resources_.barriers(frame);
    const vk::Image& shadowMap = *resources_.depthAttachment(frame.targets);
    const std::optional<TexelRect> rect = updateRect(frame, shadowMap);
    if (!rect || !rect->empty()) {
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = shadowMap.view();
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        // A rectangle keeps the rest of the map (the barrier keeps its contents: the attachment is read-write).
        depth.loadOp = rect ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {1.0f, 0};
        beginSceneRendering(frame.cmd, {shadowMap.width(), shadowMap.height()}, {}, depth);
        if (rect) {
            // Cleared and redrawn inside the rectangle alone: the rasterizer discards what falls outside the
            // scissor, and the depths inside are the ones a whole redraw writes (the same triangles, the same
            // order), so every pass reading the map sees the same values.
            const VkRect2D area{{rect->min.x, rect->min.y},
                                {uint32_t(rect->max.x - rect->min.x), uint32_t(rect->max.y - rect->min.y)}};
            VkClearAttachment clear{};
            clear.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
            clear.clearValue.depthStencil = {1.0f, 0};
            const VkClearRect clearRect{area, 0, 1};
            vkCmdClearAttachments(frame.cmd, 1, &clear, 1, &clearRect);
            vkCmdSetScissor(frame.cmd, 0, 1, &area);
        }
        // With no shadow-casting light the map stays cleared (lit everywhere) and nothing is drawn.
        if (frame.scene.shadowLightIndex() >= 0) {
            vkCmdSetDepthBias(frame.cmd, frame.settings.shadowDepthBias, 0.0f,
                              frame.settings.shadowSlopeBias);
            drawScene(frame, pipeline_, resources_);
        }
        vkCmdEndRendering(frame.cmd);
    }
    lastRect_ = rect;
    drawnImage_ = shadowMap.handle();
    drawnLight_ = frame.scene.shadowLightIndex();
    drawnLightViewProj_ = frame.scene.lightViewProj();
    drawnBiases_ = glm::vec2(frame.settings.shadowDepthBias, frame.settings.shadowSlopeBias);
}

}  // namespace vct
