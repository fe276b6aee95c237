// Which voxels a frame must update when instances moved (docs/design.md §5.9): the voxel passes then resolve,
// inject and filter only those, and leave the rest of the grid as the last frame made it.
#pragma once

#include <optional>

#include "render/gpu_scene.h"
#include "render/settings.h"
#include "render/voxel_grid.h"

namespace vct {

// The regions for this frame, or nullopt when the whole grid must be updated: the first frame, a cut, a
// changed light, --recompute-every-frame, multiple bounces (bounced light changes everywhere), or regions
// that would cover most of the grid anyway.
//  - resolve: the voxels the moved instances' bounds touch, before and after the move (margin: one voxel,
//    the voxelizer's reach beyond a triangle's bounds);
//  - inject: those, swept away from the main light to the edge of the scene's geometry (the voxels whose shadowing the move
//    may change), with a margin for the shadow lookup's offset and filter.
std::optional<VoxelGrid::UpdateRegions> voxelUpdateRegions(const VoxelGrid& grid, const GpuScene& scene,
                                                           const RenderSettings& settings, bool fullUpdate);

}  // namespace vct
