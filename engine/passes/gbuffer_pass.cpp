#include "passes/gbuffer_pass.h"

#include <algorithm>

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

// Runs remembered: a target image holds the drawing of one of the last two runs (depth and normal swap with their
// history copies each run), or older ones when the camera stood still.
constexpr size_t kKeptRuns = 4;

// A rectangle's edges fall on the 2×2 quads' (screen-space derivatives, for Toksvig and specular AA, are taken
// over quads): a quad the scissor cut in two rounded differently on lavapipe from the same quad in a whole
// drawing (cornell at 320×180: one pixel's roughness one fp16 step off with edges on odd pixels).
constexpr int kQuad = 2;

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

GBufferPass::Inputs GBufferPass::inputsOf(const FrameContext& frame) const {
    Inputs inputs;
    std::memset(&inputs, 0, sizeof(inputs));  // compared bytewise, padding included
    const gpu::FrameUniforms& u = frame.uniforms;
    inputs.viewProj = u.viewProj;
    inputs.prevViewProj = u.prevViewProj;
    inputs.view = viewInputsOf(u);
    return inputs;
}

std::optional<TexelRect> GBufferPass::updateRect(const FrameContext& frame,
                                                 const std::vector<const vk::Image*>& targets,
                                                 const Run& run) const {
    if (frame.settings.recomputeEveryFrame) return std::nullopt;
    // The oldest drawing any target holds: every run since (and that run itself, whose motion vectors the moves
    // it followed set) moved instances alone, with the same camera.
    const uint64_t firstKept = runCount_ - runs_.size();
    uint64_t oldest = runCount_;
    for (const vk::Image* image : targets) {
        const auto drawn = drawnBy_.find(image->handle());
        if (drawn == drawnBy_.end() || drawn->second < firstKept) return std::nullopt;
        oldest = std::min(oldest, drawn->second);
    }
    if (!run.onlyInstancesMoved) return std::nullopt;
    Aabb moved = run.movedBounds;
    for (uint64_t i = oldest; i < runCount_; ++i) {
        const Run& earlier = runs_[size_t(i - firstKept)];
        if (!earlier.onlyInstancesMoved || !(earlier.inputs == run.inputs)) return std::nullopt;
        moved.extend(earlier.movedBounds);
    }
    std::optional<TexelRect> rect =
        movedRect(frame.uniforms.viewProj, moved, {frame.targets.width, frame.targets.height});
    if (rect && !rect->empty()) {
        rect->min = rect->min / kQuad * kQuad;
        rect->max = glm::min((rect->max + kQuad - 1) / kQuad * kQuad,
                             glm::ivec2(int(frame.targets.width), int(frame.targets.height)));
    }
    return rect;
}

void GBufferPass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    resources_.barriers(frame);
    std::vector<const vk::Image*> targets;
    for (const vk::Image* image : resources_.colorAttachments(t)) targets.push_back(image);
    targets.push_back(resources_.depthAttachment(t));
    const Run run{inputsOf(frame), frame.scene.onlyInstancesMovedInLastUpdate(), frame.scene.movedBounds()};
    const std::optional<TexelRect> rect = updateRect(frame, targets, run);
    if (!rect || !rect->empty()) {
        // A rectangle keeps the rest of every target (the barriers keep their contents).
        const VkAttachmentLoadOp load = rect ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
        std::vector<VkRenderingAttachmentInfo> colors;
        std::vector<VkClearAttachment> clears;
        for (const vk::Image* image : resources_.colorAttachments(t)) {
            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = image->view();
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = load;
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            color.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
            clears.push_back({VK_IMAGE_ASPECT_COLOR_BIT, uint32_t(colors.size()), color.clearValue});
            colors.push_back(color);
        }
        VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depth.imageView = resources_.depthAttachment(t)->view();
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
        depth.loadOp = load;
        depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depth.clearValue.depthStencil = {1.0f, 0};
        clears.push_back({VK_IMAGE_ASPECT_DEPTH_BIT, 0, depth.clearValue});
        beginSceneRendering(frame.cmd, {t.width, t.height}, colors, depth);
        if (rect) {
            // Cleared and redrawn inside the rectangle alone, as the shadow pass does its map.
            const VkRect2D area{{rect->min.x, rect->min.y},
                                {uint32_t(rect->max.x - rect->min.x), uint32_t(rect->max.y - rect->min.y)}};
            const VkClearRect clearRect{area, 0, 1};
            vkCmdClearAttachments(frame.cmd, uint32_t(clears.size()), clears.data(), 1, &clearRect);
            vkCmdSetScissor(frame.cmd, 0, 1, &area);
        }
        // Blended surfaces are drawn forward by the blend pass, after the opaque frame (docs/design.md §2.6).
        drawScene(frame, pipelines_, resources_, kPreviousVertices, DrawSet::Opaque);
        vkCmdEndRendering(frame.cmd);
    }
    lastRect_ = rect;
    for (const vk::Image* image : targets) drawnBy_[image->handle()] = runCount_;
    runs_.push_back(run);
    ++runCount_;
    if (runs_.size() > kKeptRuns) runs_.erase(runs_.begin());
    std::erase_if(drawnBy_, [&](const auto& entry) { return entry.second + kKeptRuns < runCount_; });
}

}  // namespace vct
