#include "passes/gbuffer_pass.h"

#include "render/scene_draw.h"

namespace vct {

namespace {

// Last frame's deformed vertices (shaders/gbuffer.vert: the motion of skinned and morphed instances), written
// by drawScene; the skin pass's barrier makes them visible to the vertex shader.
constexpr uint32_t kPreviousVertices = 8;

ResourceTable gbufferResources() {
    std::vector<ResourceRow> rows = sceneDrawRows();
    rows.push_back({kPreviousVertices, Resource::perDraw("previousVertices", true), Access::Read,
                    VK_SHADER_STAGE_VERTEX_BIT});
    // The colour attachments in the order of gbuffer.frag's outputs (location 0, 1, …), then the depth.
    for (Target target :
         {Target::normalRoughness, Target::baseColorMetallic, Target::emissiveOcclusion, Target::motion})
        rows.push_back({kNoBinding, target, Access::ColorAttachment});
    rows.push_back({kNoBinding, Target::depth, Access::DepthAttachment});
    return {"gbuffer", std::move(rows)};
}

}  // namespace

GBufferPass::GBufferPass(const vk::Context& context, const Scene& scene, bool vertexColors, bool textureLod0)
    : resources_(gbufferResources()),
      pipelines_(context, pipelineDesc(vertexColors), scene, DrawSet::Opaque, textureLod0) {}

vk::Pipeline::GraphicsDesc GBufferPass::pipelineDesc(bool vertexColors) const {
    vk::Pipeline::GraphicsDesc desc;
    desc.owner = name();
    desc.vertexShader = "gbuffer.vert";
    desc.fragmentShader = "gbuffer.frag";
    desc.colorFormats = resources_.colorFormats();
    desc.depthFormat = resources_.depthFormat();
    desc.bindings = resources_.bindings();
    desc.pushConstantSize = sizeof(gpu::DrawPushConstants);
    desc.specialization = {vertexColors ? 1u : 0u};  // VCT_SPEC_VERTEX_COLORS
    return desc;
}

void GBufferPass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    resources_.barriers(frame);
    std::vector<VkRenderingAttachmentInfo> colors;
    for (const vk::Image* image : resources_.colorAttachments(t)) {
        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = image->view();
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        color.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        colors.push_back(color);
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = resources_.depthAttachment(t)->view();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};
    beginSceneRendering(frame.cmd, {t.width, t.height}, colors, depth);
    // Blended surfaces are drawn forward by the blend pass, after the opaque frame (docs/design.md §2.6).
    drawScene(frame, pipelines_, resources_, kPreviousVertices, DrawSet::Opaque);
    vkCmdEndRendering(frame.cmd);
}

}  // namespace vct
