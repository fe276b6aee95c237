// upsample: brings the low-res demodulated indirect light (trace) to full resolution. For now a plain bilinear
// filter; the lobe-aware spatio-temporal upsampling (DESIGN §3.5) replaces it.
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class UpsamplePass : public Pass {
public:
    explicit UpsamplePass(const vk::Context& context);
    const char* name() const override { return "upsample"; }
    std::vector<ImageUse> uses(FrameTargets& targets) override;
    void execute(const FrameContext& frame) override;

private:
    vk::Pipeline pipeline_;
};

}  // namespace vct
