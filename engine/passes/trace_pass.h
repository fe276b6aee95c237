// trace: voxel cone tracing at 1/traceScale resolution (docs/design.md §5): 6 diffuse cones and 1 specular cone
// per low-res pixel, from the full-res G-buffer at pixel (s·x, s·y), through the voxel grid's radiance mips.
// Writes demodulated diffuse and specular indirect light (lib/cone.glsl) to the low-res targets.
#pragma once

#include "render/gpu_environment.h"
#include "render/pass.h"
#include "render/voxel_grid.h"
#include "vk/pipeline.h"

namespace vct {

// What cone tracing reads from the voxel grid (lib/cone_trace.glsl): premultiplied radiance (rgb) + opacity (a),
// mips 1.. in one 3D RGBA16F texture with its trilinear sampler, mip 0 in the radiance atlas with its own, and
// the brick table that finds a brick's block in the atlas.
struct VoxelSource {
    vk::Image* radianceMips = nullptr;
    VkSampler sampler = VK_NULL_HANDLE;
    vk::Image* radianceAtlas = nullptr;
    VkSampler atlasSampler = VK_NULL_HANDLE;
    vk::Buffer* brickTable = nullptr;
    bool sparseMip0 = false;        // mip 0 in the atlas (VCT_SPEC_SPARSE_MIP0)
    EnvironmentSource environment;  // what a cone that leaves the grid sees (lib/cone_trace.glsl)

    std::vector<uint32_t> specialization(std::vector<uint32_t> first = {}) const {
        return withSparseMip0(std::move(first), sparseMip0);  // render/voxel_grid.h
    }

    // Its rows in a pass's table: the mips at binding `mipsBinding`, the atlas and the brick table at theirs
    // (VCT_BINDING_VOXEL_ATLAS, VCT_BINDING_BRICKS).
    void addRows(std::vector<ResourceRow>& rows, uint32_t mipsBinding,
                 VkShaderStageFlags stages = VK_SHADER_STAGE_COMPUTE_BIT) const {
        rows.push_back(
            {mipsBinding, Resource::image("voxels", *radianceMips, sampler), Access::Sampled, stages});
        rows.push_back({VCT_BINDING_VOXEL_ATLAS,
                        Resource::image("radianceAtlas", *radianceAtlas, atlasSampler), Access::Sampled,
                        stages});
        rows.push_back({VCT_BINDING_BRICKS, Resource::buffer("bricks", *brickTable), Access::Read, stages});
    }
};

class TracePass : public Pass {
  public:
    // Trace scale 1 writes the full-res indirect targets directly (no upsample pass follows).
    TracePass(const vk::Context& context, uint32_t traceScale, const VoxelSource& voxels);
    const char* name() const override { return "trace"; }
    void execute(const FrameContext& frame) override;

  private:
    // Trace scale 1: the full-res result itself (no upsample pass runs); else the low-res one.
    Target output_;
    ResourceTable resources_;
    vk::Pipeline pipeline_;
};

}  // namespace vct
