// resample: adaptive re-tracing (docs/design.md §6.6). Traces, at full resolution, only the pixels the upsample
// pass listed (sum of weights < τ), through an indirect dispatch sized by that list, and overwrites their
// upsampled indirect light; then copies the list's length back for `resampled_fraction`.
#pragma once

#include "passes/trace_pass.h"
#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

class ResamplePass : public Pass {
  public:
    // `coneLanes`: traceConeLanes (passes/trace_pass.h).
    ResamplePass(const vk::Context& context, uint32_t coneLanes, const VoxelSource& voxels);
    const char* name() const override { return "resample"; }
    void execute(const FrameContext& frame) override;

  private:
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
