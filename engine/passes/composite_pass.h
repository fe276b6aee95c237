// composite: the frame's linear HDR result — direct light plus, with GI on, the indirect light re-modulated:
// albedo·diffuse·occlusion + specularDfg(F0, DFG(n·v, roughness))·specular (multiple-scattering energy
// compensation, docs/design.md §3.3), with the blend pass's layer of blended surfaces over it — and its
// tone-mapped sRGB version for the PNG and the window.
#pragma once

#include "render/dfg_lut.h"
#include "render/gpu_scene.h"
#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class CompositePass : public Pass {
  public:
    // `dfg`: the split-sum table (the renderer's, shared with inject and blend). `gi`: RenderSettings::gi.
    // Specialization constants: `gi`, and whether `scene` has blended surfaces (the blend pass runs) and
    // occlusion.
    CompositePass(const vk::Context& context, DfgLut& dfg, const GpuScene& scene, bool gi);
    const char* name() const override { return "composite"; }
    // The frame's composite: the tone-mapped image alone.
    void execute(const FrameContext& frame) override;
    // The same, also writing the linear HDR image (FrameTargets::hdr), from what the last frame left in the
    // targets it reads: for Renderer::readFinalHdr, after the frame. Its pipeline is made on the first call.
    void executeWithHdr(const FrameContext& frame);

  private:
    const vk::Context& context_;
    ResourceTable resources_;
    std::vector<uint32_t> specialization_;  // VCT_COMPOSITE_SPEC_*, HDR off
    vk::Pipeline pipeline_;
    vk::Pipeline hdrPipeline_;
};

}  // namespace vct
