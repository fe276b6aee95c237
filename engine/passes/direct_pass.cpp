#include "passes/direct_pass.h"

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
                       const GpuScene& scene, bool gi)
    : resources_(directResources(environment)) {
    std::vector<uint32_t> specialization(VCT_DIRECT_SPEC_OCCLUSION + 1);
    specialization[VCT_DIRECT_SPEC_GI] = gi ? 1u : 0u;
    specialization[VCT_DIRECT_SPEC_EMISSION] = scene.hasEmission() ? 1u : 0u;
    specialization[VCT_DIRECT_SPEC_OCCLUSION] = scene.hasOcclusion() ? 1u : 0u;
    pipeline_ =
        vk::Pipeline::compute(context, name(), "direct.comp", resources_.bindings(), 0, specialization);
}

void DirectPass::execute(const FrameContext& frame) {
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    vkCmdDispatch(frame.cmd, tileCount(frame.targets.width), tileCount(frame.targets.height), 1);
}

}  // namespace vct
