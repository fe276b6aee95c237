// upsample: brings the low-res demodulated indirect light (trace) back to full resolution over space and time
// with depth × lobe (or normal) weights (docs/design.md §6, shaders/upsample.comp); keeps the per-pixel sum of
// weights and lists the pixels whose sum is below τ for the resample pass (resetting that list first).
#pragma once

#include <map>

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class UpsamplePass : public Pass {
  public:
    explicit UpsamplePass(const vk::Context& context);
    const char* name() const override { return "upsample"; }
    void execute(const FrameContext& frame) override;

  private:
    // The pipeline specialized for this frame's trace scale, weights, temporal and adaptive settings
    // and on whether the image size (width × height) is a multiple of the trace scale (shaders/upsample.comp),
    // compiled the first time that combination is used.
    const vk::Pipeline& pipelineFor(const RenderSettings& settings, uint32_t width, uint32_t height);
    // One invocation per pixel (--upsample-layout pixel, or auto on a GPU) rather than per low-res cell. Trace
    // scales 2 and 4 only: a workgroup's samples must fit its 64 invocations (7² at scale 2).
    bool perPixel(const RenderSettings& settings) const;

    const vk::Context& context_;
    ResourceTable resources_;  // one table for every specialization
    std::map<uint32_t, vk::Pipeline> pipelines_;
};

}  // namespace vct
