#include "passes/composite_pass.h"

namespace vct {

CompositePass::CompositePass(const vk::Context& context, DfgLut& dfg, bool gi, bool blended)
    :  // Binding numbers: shaders/composite.comp's.
      resources_("composite",
                 {{VCT_BINDING_FRAME, Resource::frameUniforms(), Access::Uniform},
                  {1, Target::direct, Access::Read},
                  {2, Target::hdr, Access::Write},
                  {3, Target::ldr, Access::Write},
                  {4, Target::depth, Access::Sampled},
                  {5, Target::normalRoughness, Access::Sampled},
                  {6, Target::baseColorMetallic, Access::Sampled},
                  {7, Target::emissiveOcclusion, Access::Sampled},
                  // A 1×1 stand-in with GI off, which the shader does not read.
                  {8, Target::indirect, Access::Read},
                  {10, Resource::image("dfg", dfg.image(), dfg.sampler()), Access::Sampled},
                  // The blend pass's layer (a 1×1 stand-in in a scene without blended surfaces, not read).
                  {11, Target::transparent, Access::Sampled}}) {
    std::vector<uint32_t> specialization(VCT_COMPOSITE_SPEC_BLEND + 1);
    specialization[VCT_COMPOSITE_SPEC_GI] = gi ? 1u : 0u;
    specialization[VCT_COMPOSITE_SPEC_BLEND] = blended ? 1u : 0u;
    pipeline_ =
        vk::Pipeline::compute(context, name(), "composite.comp", resources_.bindings(), 0, specialization);
}

void CompositePass::execute(const FrameContext& frame) {
    pipeline_.bind(frame.cmd);
    resources_.bind(frame, pipeline_);
    vkCmdDispatch(frame.cmd, tileCount(frame.targets.width), tileCount(frame.targets.height), 1);
}

}  // namespace vct
