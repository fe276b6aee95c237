// What the passes that read the voxel grid's radiance bind (trace, resample, blend, bounce, the voxel view).
#pragma once

#include <vector>

#include "render/gpu_environment.h"
#include "render/pass_resources.h"
#include "render/voxel_grid.h"

namespace vct {

// What cone tracing reads from the voxel grid (lib/cone_trace.glsl): premultiplied radiance (rgb) + opacity (a),
// the mips' 3D RGBA16F texture with its trilinear sampler (from mip 1 when mip 0 is sparse), the radiance atlas
// with its own (mip 0 when sparse), and the brick table that finds a brick's block in the atlas.
struct VoxelSource {
    vk::Image* radianceMips = nullptr;
    VkSampler sampler = VK_NULL_HANDLE;
    vk::Image* radianceAtlas = nullptr;
    VkSampler atlasSampler = VK_NULL_HANDLE;
    vk::Buffer* brickTable = nullptr;
    vk::Image* regionLabels = nullptr;  // the static grid's region labels (render/voxel_regions.h)
    bool sparseMip0 = false;            // mip 0 in the atlas (VCT_SPEC_SPARSE_MIP0)
    bool voxelRegions = false;          // cones end at region changes (VCT_SPEC_VOXEL_REGIONS)
    EnvironmentSource environment;      // what a cone that leaves the grid sees (lib/cone_trace.glsl)

    // The grid's, with `environment` (only the cone-tracing passes need one).
    static VoxelSource of(VoxelGrid& grid, const EnvironmentSource& environment = {}) {
        return {&grid.radianceMips(), grid.sampler(),     &grid.radianceAtlas(),
                grid.atlasSampler(),  &grid.brickTable(), &grid.regionLabels(),
                grid.sparseMip0(),    grid.usesRegions(), environment};
    }

    // For a pipeline that traces cones (lib/cone_trace.glsl).
    std::vector<uint32_t> specialization(std::vector<uint32_t> first = {}) const {
        return withConeVoxels(std::move(first), sparseMip0, voxelRegions);  // render/voxel_grid.h
    }

    // Its rows in a pass's table: the mips at binding `mipsBinding`, the atlas and the brick table at theirs
    // (VCT_BINDING_VOXEL_ATLAS, VCT_BINDING_BRICKS), and for a pass that traces cones (`cones`) the region labels
    // (VCT_BINDING_VOXEL_REGIONS).
    void addRows(std::vector<ResourceRow>& rows, uint32_t mipsBinding,
                 VkShaderStageFlags stages = VK_SHADER_STAGE_COMPUTE_BIT, bool cones = true) const {
        if (cones)
            rows.push_back({VCT_BINDING_VOXEL_REGIONS, Resource::image("voxelRegions", *regionLabels),
                            Access::Sampled, stages});
        rows.push_back(
            {mipsBinding, Resource::image("voxels", *radianceMips, sampler), Access::Sampled, stages});
        rows.push_back({VCT_BINDING_VOXEL_ATLAS,
                        Resource::image("radianceAtlas", *radianceAtlas, atlasSampler), Access::Sampled,
                        stages});
        rows.push_back({VCT_BINDING_BRICKS, Resource::buffer("bricks", *brickTable), Access::Read, stages});
    }
};

}  // namespace vct
