// direct: full-resolution direct light (GGX + height-correlated Smith + Schlick, docs/design.md §3.2) from every
// punctual light, the main light shadow-mapped, plus emission and the constant ambient term.
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class DirectPass : public Pass {
  public:
    explicit DirectPass(const vk::Context& context);
    const char* name() const override { return "direct"; }
    PassReuse reuse() const override { return PassReuse::WhileViewUnchanged; }
    void execute(const FrameContext& frame) override;

  private:
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
