// direct: full-resolution direct light (GGX + height-correlated Smith + Schlick, docs/design.md §3.2) from every
// punctual light, the main light shadow-mapped, plus emission; the environment for the background and, with GI
// off, its light reflected by the surface (lib/environment_sample.glsl).
#pragma once

#include "render/gpu_environment.h"
#include "render/gpu_scene.h"
#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class DirectPass : public Pass {
  public:
    // `environment`: the background, and the ambient light with GI off (`gi`: RenderSettings::gi). Whether
    // `scene` has emission and occlusion, and `gi`, are specialization constants (lib/shared.h).
    DirectPass(const vk::Context& context, const EnvironmentSource& environment, const GpuScene& scene,
               bool gi);
    const char* name() const override { return "direct"; }
    PassReuse reuse() const override { return PassReuse::WhileViewUnchanged; }
    void execute(const FrameContext& frame) override;

  private:
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
