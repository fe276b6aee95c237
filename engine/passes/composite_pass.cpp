#include "passes/composite_pass.h"

namespace vct {

CompositePass::CompositePass(const vk::Context& context, DfgLut& dfg, const GpuScene& scene, bool gi)
    : context_(context),
      // Binding numbers: shaders/composite.comp's.
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
    specialization_.resize(VCT_COMPOSITE_SPEC_HDR + 1);
    specialization_[VCT_COMPOSITE_SPEC_GI] = gi ? 1u : 0u;
    specialization_[VCT_COMPOSITE_SPEC_BLEND] = scene.hasBlended() ? 1u : 0u;
    specialization_[VCT_COMPOSITE_SPEC_OCCLUSION] = scene.hasOcclusion() ? 1u : 0u;
    specialization_[VCT_COMPOSITE_SPEC_HDR] = 0u;
    pipeline_ =
        vk::Pipeline::compute(context, name(), "composite.comp", resources_.bindings(), 0, specialization_);
}

namespace {

void dispatchComposite(const FrameContext& frame, const ResourceTable& resources,
                       const vk::Pipeline& pipeline) {
    pipeline.bind(frame.cmd);
    resources.bind(frame, pipeline);
    vkCmdDispatch(frame.cmd, tileCount(frame.targets.width), tileCount(frame.targets.height), 1);
}

}  // namespace

void CompositePass::execute(const FrameContext& frame) {
    dispatchComposite(frame, resources_, pipeline_);
}

void CompositePass::executeWithHdr(const FrameContext& frame) {
    if (hdrPipeline_.handle() == VK_NULL_HANDLE) {
        std::vector<uint32_t> withHdr = specialization_;
        withHdr[VCT_COMPOSITE_SPEC_HDR] = 1u;
        hdrPipeline_ =
            vk::Pipeline::compute(context_, name(), "composite.comp", resources_.bindings(), 0, withHdr);
    }
    dispatchComposite(frame, resources_, hdrPipeline_);
}

}  // namespace vct
