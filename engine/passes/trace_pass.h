// trace: voxel cone tracing at 1/traceScale resolution (docs/design.md §5): 6 diffuse cones and 1 specular cone
// per low-res pixel, from the full-res G-buffer at pixel (s·x, s·y), through the voxel grid's radiance mips.
// Writes demodulated diffuse and specular indirect light (lib/cone.glsl) to the low-res targets.
#pragma once

#include "render/pass.h"
#include "vk/pipeline.h"

namespace vct {

// What the trace reads from the voxel grid: a 3D RGBA16F texture with a full mip chain of premultiplied
// radiance (rgb) + opacity (a), and a trilinear clamp-to-border (transparent black) sampler.
struct VoxelSource {
    vk::Image* radiance = nullptr;
    VkSampler sampler = VK_NULL_HANDLE;
};

class TracePass : public Pass {
public:
    // Trace scale 1 writes the full-res indirect targets directly (no upsample pass follows).
    TracePass(const vk::Context& context, uint32_t traceScale);
    ~TracePass() override;
    const char* name() const override { return "trace"; }
    std::vector<ImageUse> uses(FrameTargets& targets) override;
    void execute(const FrameContext& frame) override;

    // The grid to trace; until one is set, an empty 2³ grid (no indirect light but the environment's).
    void setVoxels(const VoxelSource& source) { source_ = source; }

private:
    VoxelSource voxels() { return source_.radiance ? source_ : VoxelSource{&emptyGrid_, emptySampler_}; }

    vk::Image& output(FrameTargets& targets) const;

    VkDevice device_ = VK_NULL_HANDLE;
    bool fullResolution_ = false;
    vk::Pipeline pipeline_;
    VoxelSource source_;
    vk::Image emptyGrid_;
    VkSampler emptySampler_ = VK_NULL_HANDLE;
};

}  // namespace vct
