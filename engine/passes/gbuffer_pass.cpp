#include "passes/gbuffer_pass.h"

#include "render/scene_draw.h"

namespace vct {

GBufferPass::GBufferPass(const vk::Context& context) {
    vk::Pipeline::GraphicsDesc desc;
    desc.vertexShader = "gbuffer.vert";
    desc.fragmentShader = "gbuffer.frag";
    desc.colorFormats = {FrameTargets::kNormalRoughnessFormat, FrameTargets::kBaseColorMetallicFormat,
                         FrameTargets::kEmissiveOcclusionFormat, FrameTargets::kMotionFormat};
    desc.depthFormat = FrameTargets::kDepthFormat;
    desc.bindings = sceneDrawBindings();
    desc.pushConstantSize = sizeof(gpu::DrawPushConstants);
    pipeline_ = vk::Pipeline::graphics(context, desc);
}

std::vector<ImageUse> GBufferPass::uses(FrameTargets& t) {
    return {{&t.depth, vk::ImageAccess::DepthAttachment},
            {&t.normalRoughness, vk::ImageAccess::ColorAttachment},
            {&t.baseColorMetallic, vk::ImageAccess::ColorAttachment},
            {&t.emissiveOcclusion, vk::ImageAccess::ColorAttachment},
            {&t.motion, vk::ImageAccess::ColorAttachment}};
}

void GBufferPass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    VkRenderingAttachmentInfo colors[4];
    vk::Image* images[4] = {&t.normalRoughness, &t.baseColorMetallic, &t.emissiveOcclusion, &t.motion};
    for (int i = 0; i < 4; ++i) {
        colors[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        colors[i].imageView = images[i]->view();
        colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        colors[i].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = t.depth.view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {t.width, t.height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 4;
    rendering.pColorAttachments = colors;
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(frame.cmd, &rendering);
    VkViewport viewport{0, 0, float(t.width), float(t.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {t.width, t.height}};
    vkCmdSetViewport(frame.cmd, 0, 1, &viewport);
    vkCmdSetScissor(frame.cmd, 0, 1, &scissor);
    drawScene(frame, pipeline_);
    vkCmdEndRendering(frame.cmd);
}

}  // namespace vct
