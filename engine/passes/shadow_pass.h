// shadow: light-space depth of the main (shadow-casting) light, for the direct and (later) inject passes.
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class ShadowPass : public Pass {
  public:
    explicit ShadowPass(const vk::Context& context);
    const char* name() const override { return "shadow"; }
    PassReuse reuse() const override { return PassReuse::WhileSceneUnchanged; }
    void execute(const FrameContext& frame) override;

  private:
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
