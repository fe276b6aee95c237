#include "render/voxel_update.h"

#include <algorithm>
#include <cmath>

#include "lib/shared.h"

namespace vct {

namespace {

// Voxels of margin around the moved bounds for the resolve: the voxelizer writes the voxels a triangle's
// bounds touch (no conservative dilation beyond), so one is enough.
constexpr uint32_t kResolveMargin = 1;
// For the injected light: the shadow lookup steps up to ~1.7 voxels out along the light and the normal
// (inject.comp) and filters 2×2 shadow texels; a thin sheet's test (lib/voxel_sheet.glsl's sheetAxis) reads the
// occupancy up to 2 voxels away, whose resolve reaches a voxel further (kResolveMargin): 3 covers both.
constexpr uint32_t kInjectMargin = 3;
// Above this share of the grid a region saves little and the whole grid is updated instead.
constexpr double kMaxRegionShare = 0.5;

// Distance along unit `dir` from `p` (inside `box` or not) to where the ray leaves `box` (slab method).
float exitDistance(glm::vec3 p, glm::vec3 dir, const Aabb& box) {
    float exit = 0.0f;
    bool first = true;
    for (int k = 0; k < 3; ++k) {
        if (std::abs(dir[k]) < 1e-8f) continue;
        const float t = ((dir[k] > 0.0f ? box.max[k] : box.min[k]) - p[k]) / dir[k];
        exit = first ? t : std::min(exit, t);
        first = false;
    }
    return std::max(exit, 0.0f);
}

// `box` and its shadow: each corner swept away from the light along the light's direction (directional) or
// from its position (spot, point) until it leaves `content`, the box outside which no voxel is occupied.
Aabb withShadowSweep(const Aabb& box, const gpu::GpuLight& light, const Aabb& content) {
    Aabb swept = box;
    const bool directional = int(light.directionType.w) == VCT_LIGHT_DIRECTIONAL;
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                               (c & 4) ? box.max.z : box.min.z);
        glm::vec3 away = glm::vec3(light.directionType);
        if (!directional) {
            const glm::vec3 fromLight = corner - glm::vec3(light.positionRange);
            const float length = glm::length(fromLight);
            // A light inside the moved bounds shadows in every direction.
            if (!(length > 1e-6f)) return Aabb{glm::vec3(-1e30f), glm::vec3(1e30f)};
            away = fromLight / length;
        }
        swept.extend(corner + away * exitDistance(corner, away, content));
    }
    return swept;
}

}  // namespace

std::optional<VoxelGrid::UpdateRegions> voxelUpdateRegions(const VoxelGrid& grid, const GpuScene& scene,
                                                           const RenderSettings& settings, bool fullUpdate) {
    // `--bounces N` gathers over the whole grid, and the light it bounced changes everywhere; `--bounces all`
    // gathers a slab a frame on its own (passes/voxel_bounce_pass.h), so what moved is updated as with one.
    const bool wholeGridBounces = settings.bounces > 1 && settings.bounces != kAllBounces;
    if (fullUpdate || settings.recomputeEveryFrame || wholeGridBounces ||
        !scene.onlyInstancesMovedInLastUpdate())
        return std::nullopt;
    const Aabb& moved = scene.movedBounds();
    VoxelGrid::UpdateRegions regions{grid.regionOf(moved, kResolveMargin),
                                     grid.regionOf(moved, kInjectMargin)};
    const int shadowLight = scene.shadowLightIndex();
    if (shadowLight >= 0 && !moved.empty()) {
        // Swept only as far as the scene's geometry reaches: beyond it no voxel is occupied.
        regions.inject = grid.regionOf(
            withShadowSweep(moved, scene.lights()[size_t(shadowLight)], grid.contentBounds()), kInjectMargin);
    }
    const double all = double(grid.resolution()) * grid.resolution() * grid.resolution();
    if (double(regions.inject.voxelCount()) > kMaxRegionShare * all) return std::nullopt;
    return regions;
}

}  // namespace vct
