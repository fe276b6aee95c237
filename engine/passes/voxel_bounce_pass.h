// bounce: multiple bounces of indirect light in the voxel grid (docs/design.md §5.7). Each occupied voxel gathers
// the light arriving at it through the grid with the 6 diffuse cones (voxel_bounce.comp); inject then sends on
// direct light + albedo × that, and the mips follow. One timer scope, "bounce".
// - `--bounces N`: after the frame's inject and mips, N − 1 iterations of gather, inject and mips over the whole
//   grid, whenever the grid is rebuilt: light that has bounced up to N times.
// - `--bounces all`: the gathers persist from frame to frame (every inject adds them), and each frame one slab of the
//   grid (a layer of bricks along z; on a CPU device, at grids finer than 64³, a band of one along y) gathers again
//   from the grid as it stands, then is injected and its mips updated. Gathering from light that has already bounced k
//   times adds bounce k + 1: the grid converges to every bounce, one more per round of the slabs at least, and a slab
//   gathers from the slabs before it in the same round. The first frame starts from 4 bounces (whole-grid gathers as
//   `--bounces 4`). The gathers go on for settleFrames() after the grid last changed, then stop until it changes again.
#pragma once

#include "passes/inject_pass.h"
#include "passes/voxel_mips_pass.h"
#include "render/gpu_environment.h"
#include "render/pass.h"
#include "render/voxel_grid.h"
#include "vk/pipeline.h"

namespace vct {

class VoxelBouncePass : public Pass {
  public:
    // `bounces` ≥ 2: the number of bounces the indirect light of a pixel carries (1 needs no pass); kAllBounces:
    // every bounce, amortised over frames (then `inject` must add the gathers in every frame's inject too).
    // `coneLanes`: invocations per voxel (traceConeLanes, passes/trace_pass.h).
    VoxelBouncePass(const vk::Context& context, VoxelGrid& grid, InjectPass& inject, VoxelMipsPass& mips,
                    uint32_t bounces, uint32_t coneLanes, const EnvironmentSource& environment);
    const char* name() const override { return "bounce"; }
    void execute(const FrameContext& frame) override;
    PassReuse reuse() const override {
        return amortised() ? PassReuse::WhileVoxelLightSettled : PassReuse::WhileSceneUnchanged;
    }
    // `--bounces all`: the bands along y each layer of bricks of an N³ grid is cut into (more than one on a CPU
    // device only), the slabs the grid is cut into (one gathers per frame), the slab `i` covers, and the frames the
    // gathers go on after the grid last changed (kSettleRounds rounds of every slab).
    static uint32_t bandsPerLayer(uint32_t resolution, bool cpuDevice);
    static uint32_t slabCount(uint32_t resolution, uint32_t bands);
    static VoxelRegion slab(uint32_t resolution, uint32_t bands, uint32_t i);
    uint32_t settleFrames() const;

  private:
    bool amortised() const { return iterations_ == 0; }
    void gather(const FrameContext& frame, const std::optional<VoxelRegion>& region);
    // `iterations` × (gather over the whole grid, inject, mips): `iterations` more bounces.
    void wholeGridIterations(const FrameContext& frame, uint32_t iterations);

    VoxelGrid& grid_;
    InjectPass& inject_;
    VoxelMipsPass& mips_;
    uint32_t iterations_;  // N − 1; 0 for kAllBounces
    uint32_t bands_;       // per layer of bricks (bandsPerLayer)
    uint32_t nextSlab_ = 0;
    bool warmStarted_ = false;  // `--bounces all`: the first frame's whole-grid gathers ran
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
