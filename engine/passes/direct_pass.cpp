#include "passes/direct_pass.h"

#include "render/moved_rect.h"

namespace vct {

namespace {

// Binding numbers: shaders/direct.comp's.
ResourceTable directResources(const EnvironmentSource& environment) {
    return {"direct",
            {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
             {1, Resource::scene(SceneBuffer::Lights), Access::Read},
             {2, Target::depth, Access::Sampled},
             {3, Target::normalRoughness, Access::Sampled},
             {4, Target::baseColorMetallic, Access::Sampled},
             {5, Target::emissiveOcclusion, Access::Sampled},
             {6, Target::shadowMap, Access::SampledCompare},
             {7, Target::direct, Access::Write},
             {8, Resource::image("environment", *environment.image, environment.sampler), Access::Sampled}}};
}

}  // namespace

DirectPass::DirectPass(const vk::Context& context, const EnvironmentSource& environment,
                       const GpuScene& scene, bool gi, const ShadowPass& shadow)
    : resources_(directResources(environment)), shadow_(shadow) {
    std::vector<uint32_t> specialization(VCT_DIRECT_SPEC_OCCLUSION + 1);
    specialization[VCT_DIRECT_SPEC_GI] = gi ? 1u : 0u;
    specialization[VCT_DIRECT_SPEC_EMISSION] = scene.hasEmission() ? 1u : 0u;
    specialization[VCT_DIRECT_SPEC_OCCLUSION] = scene.hasOcclusion() ? 1u : 0u;
    pipeline_ = vk::Pipeline::compute(context, name(), "direct.comp", resources_.bindings(),
                                      sizeof(gpu::DirectPushConstants), specialization);
}

DirectPass::Inputs DirectPass::inputsOf(const FrameContext& frame) const {
    Inputs inputs;
    std::memset(&inputs, 0, sizeof(inputs));  // compared bytewise, padding included
    const gpu::FrameUniforms& u = frame.uniforms;
    inputs.invViewProj = u.invViewProj;
    inputs.lightViewProj = u.lightViewProj;
    inputs.cameraPosition = glm::vec4(u.cameraPosition, 0.0f);
    inputs.imageSize = glm::vec4(u.imageSize, u.texelSize);
    inputs.lighting = u.lighting;
    inputs.flags = u.flags;
    inputs.image = frame.targets.direct.handle();
    return inputs;
}

void DirectPass::execute(const FrameContext& frame) {
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    const glm::uvec2 size(frame.targets.width, frame.targets.height);
    // The pixels dispatched: all of them, or in a partial run the bounding rectangle of those that can change.
    TexelRect dispatched{glm::ivec2(0), glm::ivec2(size)};
    // Only instances moved, and the last run computed every pixel's light from the same camera, lights and
    // settings: what can differ is where they project (the G-buffer) and what the shadow pass redrew.
    gpu::DirectPushConstants push{};
    const Inputs inputs = inputsOf(frame);
    const std::optional<TexelRect>& shadowRect = shadow_.lastRect();
    if (last_ && *last_ == inputs && shadowRect && !frame.settings.recomputeEveryFrame &&
        frame.scene.onlyInstancesMovedInLastUpdate()) {
        const std::optional<TexelRect> pixels =
            movedRect(frame.uniforms.viewProj, frame.scene.movedBounds(), size);
        if (pixels) {
            push.changedPixels = glm::ivec4(pixels->min, pixels->max);
            push.changedShadowTexels = glm::ivec4(shadowRect->min, shadowRect->max);
            push.params.x = 1u;
            // The pixels whose shadow lookup can read the redrawn texels lie where the light's column over them
            // projects (surface points are within the instances' bounds); outside it and `pixels` a pixel would
            // return at once, so it is not dispatched.
            Aabb surfaces;
            for (const Instance& instance : frame.scene.instances()) surfaces.extend(instance.bounds);
            const std::optional<TexelRect> readers =
                shadowReadersRect(frame.uniforms.viewProj, size, frame.uniforms.lightViewProj, *shadowRect,
                                  {frame.targets.shadowMap.width(), frame.targets.shadowMap.height()},
                                  surfaces, frame.uniforms.lighting.shadowNormalOffset);
            if (readers) {
                if (pixels->empty())
                    dispatched = *readers;
                else if (readers->empty())
                    dispatched = *pixels;
                else
                    dispatched = {glm::min(pixels->min, readers->min), glm::max(pixels->max, readers->max)};
            }
        }
    }
    lastRunPartial_ = push.params.x != 0u;
    lastDispatched_ = dispatched.area();
    push.params.y = uint32_t(dispatched.min.x);
    push.params.z = uint32_t(dispatched.min.y);
    pipeline_.pushConstants(frame.cmd, &push, sizeof(push));
    if (!dispatched.empty())
        vkCmdDispatch(frame.cmd, tileCount(uint32_t(dispatched.max.x - dispatched.min.x)),
                      tileCount(uint32_t(dispatched.max.y - dispatched.min.y)), 1);
    last_ = inputs;
}

}  // namespace vct
