#include "passes/direct_pass.h"

#include "render/moved_rect.h"

namespace vct {

namespace {

Resource directList() {
    return Resource::targetBuffer("directList", &FrameTargets::directList);
}

// Binding numbers: shaders/direct_select.comp's.
ResourceTable selectResources() {
    return {"direct select",
            {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
             {2, Target::depth, Access::Sampled},
             {3, Target::normalRoughness, Access::Sampled},
             // Its header set here first (execute), appended to by the shader.
             {10, directList(), Access::ReadWrite}}};
}

// Binding numbers: shaders/direct.comp's.
ResourceTable directResources(const EnvironmentSource& environment) {
    std::vector<ResourceRow> rows{
        {VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
        {1, Resource::scene(SceneBuffer::Lights), Access::Read},
        {2, Target::depth, Access::Sampled},
        {3, Target::normalRoughness, Access::Sampled},
        {4, Target::baseColorMetallic, Access::Sampled},
        {5, Target::emissiveOcclusion, Access::Sampled},
        {6, Target::shadowMap, Access::SampledCompare},
        {7, Target::direct, Access::Write},
        // The list of a partial run: its entries and its indirect dispatch (the LIST pipeline's).
        {10, directList(), Access::Read},
        {kNoBinding, directList(), Access::IndirectRead}};
    environment.addRows(rows, 8);
    return {"direct", std::move(rows)};
}

}  // namespace

DirectPass::DirectPass(const vk::Context& context, const EnvironmentSource& environment,
                       const GpuScene& scene, bool gi, const ShadowPass& shadow)
    : resources_(directResources(environment)), selectResources_(selectResources()), shadow_(shadow) {
    std::vector<uint32_t> specialization(VCT_DIRECT_SPEC_LIST + 1);
    specialization[VCT_DIRECT_SPEC_GI] = gi ? 1u : 0u;
    specialization[VCT_DIRECT_SPEC_EMISSION] = scene.hasEmission() ? 1u : 0u;
    specialization[VCT_DIRECT_SPEC_OCCLUSION] = scene.hasOcclusion() ? 1u : 0u;
    pipeline_ =
        vk::Pipeline::compute(context, name(), "direct.comp", resources_.bindings(), 0, specialization);
    specialization[VCT_DIRECT_SPEC_LIST] = 1u;
    listPipeline_ =
        vk::Pipeline::compute(context, name(), "direct.comp", resources_.bindings(), 0, specialization);
    selectPipeline_ = vk::Pipeline::compute(context, name(), "direct_select.comp",
                                            selectResources_.bindings(), sizeof(gpu::DirectPushConstants));
}

DirectPass::Inputs DirectPass::inputsOf(const FrameContext& frame) const {
    Inputs inputs;
    std::memset(&inputs, 0, sizeof(inputs));  // compared bytewise, padding included
    const gpu::FrameUniforms& u = frame.uniforms;
    inputs.invViewProj = u.invViewProj;
    inputs.lightViewProj = u.lightViewProj;
    inputs.view = viewInputsOf(u);
    inputs.lighting = u.lighting;
    inputs.image = frame.targets.direct.handle();
    return inputs;
}

void DirectPass::execute(const FrameContext& frame) {
    FrameTargets& t = frame.targets;
    const glm::uvec2 size(t.width, t.height);
    // Only instances moved, and the last run computed every pixel's light from the same camera, lights and
    // settings: what can differ is where they project (the G-buffer) and what the shadow pass redrew.
    const Inputs inputs = inputsOf(frame);
    const std::optional<TexelRect>& shadowRect = shadow_.lastRect();
    std::optional<TexelRect> pixels;
    if (last_ && *last_ == inputs && shadowRect && !frame.settings.recomputeEveryFrame &&
        frame.scene.onlyInstancesMovedInLastUpdate())
        pixels = movedRect(frame.uniforms.viewProj, frame.scene.movedBounds(), size);
    last_ = inputs;
    lastRunPartial_ = pixels.has_value();
    if (!pixels) {
        // Every pixel.
        pipeline_.bind(frame.cmd);
        resources_.bind(frame, pipeline_);
        vkCmdDispatch(frame.cmd, tileCount(size.x), tileCount(size.y), 1);
        lastDispatched_ = uint64_t(size.x) * size.y;
        return;
    }
    // The pixels whose shadow lookup can read the redrawn texels lie where the light's column over them projects
    // (surface points are within the instances' bounds); outside it and `pixels` a pixel keeps its value, so it is
    // not dispatched at all. The selection lists the pixels inside that do change; direct shades only those.
    TexelRect dispatched{glm::ivec2(0), glm::ivec2(size)};
    Aabb surfaces;
    for (const Instance& instance : frame.scene.instances()) surfaces.extend(instance.bounds);
    const std::optional<TexelRect> readers = shadowReadersRect(
        frame.uniforms.viewProj, size, frame.uniforms.lightViewProj, *shadowRect,
        {t.shadowMap.width(), t.shadowMap.height()}, surfaces, frame.uniforms.lighting.shadowNormalOffset);
    if (readers) {
        if (pixels->empty())
            dispatched = *readers;
        else if (readers->empty())
            dispatched = *pixels;
        else
            dispatched = {glm::min(pixels->min, readers->min), glm::max(pixels->max, readers->max)};
    }
    lastDispatched_ = dispatched.area();
    // An empty list whose indirect dispatch is (0, 1, 1) groups; the selection counts x up. (Last frame's direct
    // may still read the list: use() orders the update after it.)
    const gpu::ResampleListHeader empty{{0, 0, 0, 0}, {0, 1, 1, 0}};
    t.directList.use(frame.cmd, vk::BufferAccess::TransferWrite);
    vkCmdUpdateBuffer(frame.cmd, t.directList.handle(), 0, sizeof(empty), &empty);
    if (!dispatched.empty()) {
        gpu::DirectPushConstants push{};
        push.changedPixels = glm::ivec4(pixels->min, pixels->max);
        push.changedShadowTexels = glm::ivec4(shadowRect->min, shadowRect->max);
        push.params = glm::uvec4(0u, uint32_t(dispatched.min.x), uint32_t(dispatched.min.y), 0u);
        selectPipeline_.bind(frame.cmd);
        selectResources_.bind(frame, selectPipeline_);
        selectPipeline_.pushConstants(frame.cmd, &push, sizeof(push));
        vkCmdDispatch(frame.cmd, tileCount(uint32_t(dispatched.max.x - dispatched.min.x)),
                      tileCount(uint32_t(dispatched.max.y - dispatched.min.y)), 1);
    }
    listPipeline_.bind(frame.cmd);
    resources_.bind(frame, listPipeline_);
    vkCmdDispatchIndirect(frame.cmd, t.directList.handle(), offsetof(gpu::ResampleListHeader, dispatch));
}

}  // namespace vct
