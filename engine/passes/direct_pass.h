// direct: full-resolution direct light (GGX + height-correlated Smith + Schlick, docs/design.md §3.2) from every
// punctual light, the main light shadow-mapped, plus emission; the environment for the background and, with GI
// off, its light reflected by the surface (lib/environment_sample.glsl). When only instances moved since the last
// frame it recomputes only the pixels where they project and those whose shadow lookup reads texels the shadow
// pass redrew (docs/design.md §5.8).
#pragma once

#include <cstring>
#include <glm/glm.hpp>
#include <optional>

#include "passes/shadow_pass.h"
#include "render/gpu_environment.h"
#include "render/gpu_scene.h"
#include "render/moved_rect.h"
#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class DirectPass : public Pass {
  public:
    // `environment`: the background, and the ambient light with GI off (`gi`: RenderSettings::gi). Whether
    // `scene` has emission and occlusion, and `gi`, are specialization constants (lib/shared.h).
    // `shadow`: the pass that draws the shadow map before this one (what it redrew).
    DirectPass(const vk::Context& context, const EnvironmentSource& environment, const GpuScene& scene,
               bool gi, const ShadowPass& shadow);
    const char* name() const override { return "direct"; }
    PassReuse reuse() const override { return PassReuse::WhileViewUnchanged; }
    void execute(const FrameContext& frame) override;
    // Whether the last run recomputed only what moved instances can change (false: every pixel).
    bool lastRunPartial() const { return lastRunPartial_; }
    // A frame that skipped the pass (nothing it depends on changed): nothing recomputed.
    void skipped() override {
        lastRunPartial_ = false;
        lastDispatched_ = 0;
    }
    // The pixels the last run dispatched (all of them, or a rectangle in a partial run; 0 when skipped).
    uint64_t lastDispatched() const { return lastDispatched_; }

  private:
    // What the direct light depends on besides the G-buffer, the shadow map and the lights (which stay the same
    // while only instances move): the frame uniforms it reads, and the image it writes.
    struct Inputs {
        glm::mat4 invViewProj, lightViewProj;
        ViewInputs view;
        gpu::LightingUniforms lighting;
        VkImage image;
        bool operator==(const Inputs& other) const { return std::memcmp(this, &other, sizeof(Inputs)) == 0; }
    };
    Inputs inputsOf(const FrameContext& frame) const;

    ResourceTable resources_;
    ResourceTable selectResources_;  // direct_select.comp's
    vk::Pipeline pipeline_;          // every pixel
    vk::Pipeline listPipeline_;      // the listed pixels (VCT_DIRECT_SPEC_LIST)
    vk::Pipeline selectPipeline_;
    const ShadowPass& shadow_;
    std::optional<Inputs> last_;  // of the last run (none yet)
    bool lastRunPartial_ = false;
    uint64_t lastDispatched_ = 0;
};

}  // namespace vct
