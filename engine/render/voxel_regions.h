// Closed regions of the static voxel grid (docs/design.md §5.6): the empty voxels, labelled by the 6-connected
// component they belong to, so that a cone can end where it passes from one closed region into another (a turned
// room's walls, the wall between two rooms) instead of leaking through a wall one voxel thick.
//
// Why: a cone counts a coverage once (coneCompositeNested), so a wall that only ever covers part of its footprint
// lets the rest through. Axis-aligned rooms are closed by the closure box (render/voxel_bricks.h), whose faces are
// their walls; a room turned off the grid's axes is a staircase of voxels inside the box, and 5–6 % of its cones
// reached the sky through it (round 28: the turned emissive furnace gathered 0.83 of its radiance at 64³). The
// voxels that hold a surface (the voxelizer's own rule, voxelHoldsTriangle) separate the 6-connected empty voxels
// on either side of a closed wall, so a flood fill over the empty voxels finds the room and what lies outside it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "render/voxel_bricks.h"
#include "scene/scene.h"

namespace vct {

// Components smaller than this many voxels get no label (0): a pocket under a sphere's contact, between two boxes.
// A cone starting there takes the first labelled region it reaches as its own, so a sealed gap never darkens it.
constexpr uint32_t kMinRegionVoxels = 64;
// Labels are 8 bits (the shaders' R8_UINT volume): 255 regions at most, the ones that matter first (below).
constexpr uint32_t kMaxRegionLabels = 255;

struct VoxelRegions {
    uint32_t resolution = 0;
    // N³ labels in voxelLinearIndex order (x fastest): 0 for a voxel that holds a static surface or lies in a pocket
    // of fewer than kMinRegionVoxels, else its region's label, 1 .. kMaxRegionLabels.
    std::vector<uint8_t> labels;
    uint32_t components = 0;  // 6-connected components of the empty voxels, every size
    uint32_t labelled = 0;    // of them, those that got a label
    // Regions that light can come from, with a voxel inside the closure box: `open` ones (touching the grid's
    // border: the sky lies beyond) and `lit` ones (a static surface faces into them). Cones need the labels only
    // when two or more such regions share the box; the box alone closes the rest (an axis-aligned room, whose
    // walls are the box's faces, and any open scene: one region).
    uint32_t lightRegionsInClosure = 0;
    bool needed() const { return lightRegionsInClosure >= 2; }
    // One line for the log and the report: regions, labelled, whether cones use them.
    std::string summary() const;
};

// The voxels that hold a static triangle of the scene in the grid (origin, voxel size) of N³ voxels, as the
// voxelizer decides it (shaders/voxelize.comp: snapped vertices, voxelHoldsTriangle), in voxelLinearIndex order.
std::vector<uint8_t> staticSurfaceVoxels(const Scene& scene, glm::vec4 originSize, uint32_t resolution);

// The scene's regions in that grid; `closure` is where its cones close (VoxelGrid::coneClosure()).
VoxelRegions labelVoxelRegions(const Scene& scene, glm::vec4 originSize, uint32_t resolution,
                               const ConeClosureBox& closure);

}  // namespace vct
