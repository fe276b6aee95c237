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

void ShadowPass::execute(const FrameContext& frame) {
    resources_.barriers(frame);
    const vk::Image& shadowMap = *resources_.depthAttachment(frame.targets);
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = shadowMap.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    beginSceneRendering(frame.cmd, {shadowMap.width(), shadowMap.height()}, {}, depth);
    // With no shadow-casting light the map stays cleared (lit everywhere) and nothing is drawn.
    if (frame.scene.shadowLightIndex() >= 0) {
        vkCmdSetDepthBias(frame.cmd, frame.settings.shadowDepthBias, 0.0f, frame.settings.shadowSlopeBias);
        drawScene(frame, pipeline_, resources_);
    }
    vkCmdEndRendering(frame.cmd);
}

}  // namespace vct
