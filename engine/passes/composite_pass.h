// composite: the frame's linear HDR result — direct light plus, with GI on, the indirect light re-modulated:
// albedo·diffuse·occlusion + specularDfg(F0, DFG(n·v, roughness))·specular (multiple-scattering energy
// compensation, docs/design.md §3.3), with the blend pass's layer of blended surfaces over it — and its
// tone-mapped sRGB version for the PNG and the window.
#pragma once

#include "render/dfg_lut.h"
#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class CompositePass : public Pass {
  public:
    // `dfg`: the split-sum table (the renderer's, shared with inject and blend). `gi`: RenderSettings::gi;
    // `blended`: whether the scene has blended surfaces (the blend pass runs). Both specialization constants.
    CompositePass(const vk::Context& context, DfgLut& dfg, bool gi, bool blended);
    const char* name() const override { return "composite"; }
    void execute(const FrameContext& frame) override;

  private:
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
