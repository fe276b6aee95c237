// trace: voxel cone tracing at 1/traceScale resolution (docs/design.md §5): 6 diffuse cones and 1 specular cone
// per low-res pixel, from the full-res G-buffer at pixel (s·x, s·y), through the voxel grid's radiance mips.
// Writes demodulated diffuse and specular indirect light (lib/cone.glsl) to the low-res targets.
#pragma once

#include "passes/voxel_source.h"
#include "render/pass.h"
#include "render/settings.h"
#include "vk/pipeline.h"

namespace vct {

// Invocations per pixel or voxel of the trace, resample and bounce pipelines (VCT_SPEC_CONE_LANES,
// lib/cone_trace.glsl): 1 for the pixel layout, VCT_CONE_LANES_PER_PIXEL for the cone layout; auto picks by device
// type (the cone layout on a GPU).
uint32_t traceConeLanes(const vk::Context& context, RenderSettings::TraceLayout layout);

class TracePass : public Pass {
  public:
    // Trace scale 1 writes the full-res indirect targets directly (no upsample pass follows). `coneLanes`:
    // traceConeLanes.
    TracePass(const vk::Context& context, uint32_t traceScale, uint32_t coneLanes, const VoxelSource& voxels);
    const char* name() const override { return "trace"; }
    void execute(const FrameContext& frame) override;

  private:
    // Trace scale 1: the full-res result itself (no upsample pass runs); else the low-res one.
    Target output_;
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
