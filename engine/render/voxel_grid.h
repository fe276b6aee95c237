// The voxel grid of voxel cone tracing (docs/design.md §5.1): an N³ cube fitted to the scene's bounds, its
// resolved material volumes and the premultiplied radiance + opacity texture with its mip chain. Owned by the
// Renderer (only when GI is on); written by the voxelize, inject and mips passes, read by the trace pass.
//
// Conventions (shared with shaders/lib/voxel.glsl and FrameUniforms::voxels):
//  - origin() is the world position of the grid's min corner, voxelSize() the edge of one voxel; the grid
//    spans origin .. origin + N·voxelSize on every axis (a cube, one voxel of padding around the bounds).
//  - Voxel i (integer xyz, 0..N−1) covers [origin + i·size, origin + (i+1)·size); its texel centre is
//    origin + (i + 0.5)·voxelSize. Texture coordinate of a world point: UVW = (p − origin) / (N·voxelSize).
//  - Mip level m has max(1, N >> m)³ texels, each the 2×2×2 premultiplied average of level m−1; a texel of
//    level m spans 2^m voxels. mipCount() = log2(N) + 1 (down to 1³).
//  - Radiance: RGBA16F, rgb = outgoing radiance × opacity, a = opacity (premultiplied), in six direction slabs.
//    Mip 0 is sparse, in the radiance atlas (docs/design.md §5.10); mips 1.. are dense, in radianceMips()
//    (its level m − 1 holds mip m), sampled with sampler(): trilinear within the nearest level (a read between
//    levels blends two reads: lib/cone_trace.glsl), clamped to the edge.
//  - Sparse storage: only the bricks of VCT_VOXEL_BRICK³ voxels the scene can reach have storage (bricks(),
//    render/voxel_bricks.h): the accumulators, the material atlases and the radiance atlas hold those alone.
//  - N is a power of two in 32..256. Default (settings.voxelResolution = 0): 64 on a CPU device (lavapipe),
//    128 on a GPU.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "io/vdb_io.h"
#include "render/settings.h"
#include "render/voxel_bricks.h"
#include "render/voxel_regions.h"
#include "scene/scene.h"
#include "vk/buffer.h"
#include "vk/image.h"
#include "vk/sampler.h"

namespace vct {

// The N the grid gets for these settings on this device (validated: a power of two in 32..256). Without
// --voxels but with a voxel cache, the cache's N.
uint32_t chooseVoxelResolution(const vk::Context& context, const RenderSettings& settings);

// The specialization of a pipeline reading the radiance's mip 0: the shader's own constants `first`
// (constant_id 0, 1, ...), then VCT_SPEC_SPARSE_MIP0.
inline std::vector<uint32_t> withSparseMip0(std::vector<uint32_t> first, bool sparseMip0) {
    first.resize(std::max<size_t>(first.size(), VCT_SPEC_SPARSE_MIP0 + 1), 0u);
    first[VCT_SPEC_SPARSE_MIP0] = sparseMip0 ? 1u : 0u;
    return first;
}
// The same for a pipeline that traces cones: also VCT_SPEC_VOXEL_REGIONS (render/voxel_regions.h).
inline std::vector<uint32_t> withConeVoxels(std::vector<uint32_t> first, bool sparseMip0, bool voxelRegions) {
    first = withSparseMip0(std::move(first), sparseMip0);
    first.resize(std::max<size_t>(first.size(), VCT_SPEC_VOXEL_REGIONS + 1), 0u);
    first[VCT_SPEC_VOXEL_REGIONS] = voxelRegions ? 1u : 0u;
    return first;
}

// World bounds the grid must cover: every instance over the scene's animation (sampled), so that moving
// geometry stays inside the grid.
Aabb voxelSceneBounds(const Scene& scene);

// A box of voxels, [min, max) on each axis at mip 0. The voxel passes update only the frame's regions
// (docs/design.md §5.9): where moving instances were or are, and for the injected light also where their
// shadows fall.
struct VoxelRegion {
    glm::uvec3 min{0u};
    glm::uvec3 max{0u};
    bool empty() const { return glm::any(glm::greaterThanEqual(min, max)); }
    uint64_t voxelCount() const;
    // The same box at mip `level`: every texel with a child in it.
    VoxelRegion atLevel(uint32_t level) const;
};

// A voxel pass over the whole grid: one workgroup per allocated brick, in rows (lib/voxel_workgroup.glsl).
inline void dispatchBricks(VkCommandBuffer cmd, uint32_t bricks) {
    if (bricks == 0) return;
    vkCmdDispatch(cmd, std::min<uint32_t>(bricks, VCT_BRICK_DISPATCH_ROW),
                  (bricks + VCT_BRICK_DISPATCH_ROW - 1) / VCT_BRICK_DISPATCH_ROW, 1);
}

// Invocations per brick of the inject and bounce passes (VCT_VOXEL_SPEC_LANES, lib/voxel_packing.glsl): 64, one per
// voxel, on a GPU, which does not run a warp none of whose lanes has a voxel; the subgroup size (lavapipe: 8 lanes
// at 256 bits) on a CPU device, whose lavapipe runs every SIMD batch of a workgroup through the code, masked, also
// those without a voxel (benchmarks/README.md, round 13).
uint32_t voxelPassLanes(const vk::Context& context);

// A voxel pass over a region: one workgroup per brick of its (brick-aligned) box (lib/voxel_workgroup.glsl).
inline void dispatchRegionBricks(VkCommandBuffer cmd, const VoxelRegion& region) {
    if (region.empty()) return;
    const glm::uvec3 bricks =
        (region.max - region.min + glm::uvec3(VCT_VOXEL_BRICK - 1)) / uint32_t(VCT_VOXEL_BRICK);
    vkCmdDispatch(cmd, bricks.x, bricks.y, bricks.z);
}

class VoxelGrid {
  public:
    // `sparseMip0`: the radiance's mip 0 in the brick atlas, else dense in radianceMips() (RenderSettings::
    // sparseMip0From).
    // `regions`: label the static grid's closed regions for the cones where the scene needs it (usesRegions()).
    VoxelGrid(const vk::Context& context, const Scene& scene, uint32_t resolution, bool sparseMip0 = true,
              bool regions = true);
    ~VoxelGrid();
    VoxelGrid(const VoxelGrid&) = delete;
    VoxelGrid& operator=(const VoxelGrid&) = delete;

    glm::vec3 origin() const { return glm::vec3(originSize_); }
    float voxelSize() const { return originSize_.w; }
    glm::vec4 originSize() const { return originSize_; }  // (origin, voxelSize), as lib/voxel.glsl takes it
    uint32_t resolution() const { return resolution_; }
    // Where the scene's geometry can be, over its whole animation (voxelSceneBounds): no voxel outside is
    // ever occupied. The grid (a cube) spans more.
    const Aabb& contentBounds() const { return contentBounds_; }
    // Where cones close (render/voxel_bricks.h's coneClosureBox).
    const ConeClosureBox& coneClosure() const { return coneClosure_; }
    // The static grid's closed regions (render/voxel_regions.h), without their labels (released once uploaded), and
    // the labels for the shaders: 3D R8_UINT, N³ when cones use them (VoxelRegions::needed), else a 1×1×2 stand-in of
    // 0 (no region: cones never end at one).
    const VoxelRegions& regions() const { return regions_; }
    bool usesRegions() const { return regions_.needed(); }
    vk::Image& regionLabels() { return regionLabels_; }
    uint32_t mipCount() const { return mipCount_; }

    // Premultiplied radiance + opacity, 3D RGBA16F (SAMPLED | STORAGE): six direction slabs side by side along x
    // (lib/voxel.glsl, directional radiance), mips from mipBase() on: its level l holds mip l + mipBase().
    // Sampled with sampler().
    vk::Image& radianceMips() { return radianceMips_; }
    bool sparseMip0() const { return sparseMip0_; }
    std::vector<uint32_t> specialization(std::vector<uint32_t> first = {}) const {
        return withConeVoxels(std::move(first), sparseMip0_, usesRegions());
    }
    // The image whose level 0 holds mip 0: the atlas or the mips' texture.
    vk::Image& mip0Image() { return sparseMip0_ ? radianceAtlas_ : radianceMips_; }
    uint32_t mipBase() const { return sparseMip0_ ? 1u : 0u; }
    VkSampler sampler() const { return sampler_.handle(); }
    // Mip 0 when sparseMip0(): the radiance atlas (lib/voxel_bricks.glsl), 3D RGBA16F (SAMPLED | STORAGE),
    // sampled with atlasSampler() (trilinear within a block, one level); else a 1×1×2 stand-in.
    vk::Image& radianceAtlas() { return radianceAtlas_; }
    VkSampler atlasSampler() const { return atlasSampler_.handle(); }
    // The brick table the shaders read (lib/voxel_storage.glsl) and the layout it came from.
    vk::Buffer& brickTable() { return brickTable_; }
    const BrickLayout& bricks() const { return bricks_; }

    // Resolved material atlases (one level, STORAGE; lib/voxel_bricks.glsl): albedo rgb + opacity a (RGBA8),
    // averaged normal (RGBA16F xyz, not renormalised: shorter where surfaces in the voxel disagree), emission
    // (RGBA16F rgb).
    vk::Image& albedo() { return albedo_; }
    vk::Image& normal() { return normal_; }
    vk::Image& emission() { return emission_; }
    // The light each occupied voxel gathers from the grid for the next bounce (RGBA16F rgb, an atlas like the
    // materials): cosine-weighted mean incoming radiance about its normal (voxel_bounce.comp).
    vk::Image& bounce() { return bounce_; }

    // Device memory of the grid's storage, and what dense N³ volumes and accumulators would take.
    struct Memory {
        uint64_t bytes = 0, denseBytes = 0;
    };
    Memory memory() const { return memory_; }

    // Fixed-point accumulators (VCT_VOXEL_ACCUM_STRIDE uints per voxel of each allocated brick, brick after
    // brick): static geometry, written once, and moving instances, cleared and rewritten every frame (absent
    // when the scene has none).
    vk::Buffer& staticAccumulator() { return staticAccum_; }
    vk::Buffer& dynamicAccumulator() { return dynamicAccum_; }
    bool hasMovingInstances() const { return dynamicAccum_.handle() != VK_NULL_HANDLE; }
    VkDeviceSize accumulatorSize() const { return staticAccum_.size(); }

    // The voxels this frame's voxel passes update (set by the renderer before they run): nullopt, the whole
    // grid; else `resolve` (voxelize's resolve: where moving instances were and are) and `inject` (it, and
    // where their shadows fall; inject and mips). Both empty: nothing moved.
    struct UpdateRegions {
        VoxelRegion resolve, inject;
    };
    const std::optional<UpdateRegions>& updateRegions() const { return updateRegions_; }
    // What this frame's inject and mips update: the region's `inject`, nullopt for the whole grid.
    std::optional<VoxelRegion> injectRegion() const {
        return updateRegions_ ? std::optional<VoxelRegion>(updateRegions_->inject) : std::nullopt;
    }
    void setUpdateRegions(std::optional<UpdateRegions> regions) { updateRegions_ = regions; }
    // The voxels that world bounds `box` touch, widened by `margin` voxels and aligned to VCT_VOXEL_TILE.
    VoxelRegion regionOf(const Aabb& box, uint32_t margin) const;

    // Whether the static accumulator holds the static geometry yet (set by the voxelize pass).
    bool staticVoxelized() const { return staticVoxelized_; }
    void markStaticVoxelized() { staticVoxelized_ = true; }

    // ---- voxel cache (vct voxelize → OpenVDB file → --voxel-cache; io/vdb_io.h) ----
    // Reads the static accumulator from `path` and stages it for upload. Throws vct::Error (one line naming
    // the file) when it is missing, not a vct voxel file, or made for another resolution, grid bounds or
    // scene (VoxelFileInfo::sceneHash against sceneContentHash). The upload itself is recorded by the
    // voxelize pass in the first frame, in place of voxelizing the static instances, so it is timed in the
    // frame where it happens.
    void loadStaticCache(const std::filesystem::path& path);
    bool hasStaticCache() const { return staticCache_.handle() != VK_NULL_HANDLE; }
    // Copies the staged voxels into the (already cleared) static accumulator; transfer stage.
    void recordStaticCacheUpload(VkCommandBuffer cmd) const;
    // Frees the staging buffer; only once the frame that recorded the upload has completed.
    void releaseStaticCache();

    // ---- readback (host copies; call between frames) ----
    // A material atlas (albedo, normal, emission or bounce) as a dense N³ volume of RGBA floats, x fastest then
    // y then z (voxelLinearIndex order), zero where no brick has storage. RGBA8 reads as value / 255.
    std::vector<glm::vec4> readVolume(vk::Image& atlas);
    // Level `mip` of the radiance per voxel, max(1, N >> mip)³ (not 6×): the largest of its six slabs, channel
    // by channel (the radiance leaving towards the side its surfaces face, and the opacity).
    std::vector<glm::vec4> readRadiance(uint32_t mip = 0);
    // The static accumulator's voxels with at least one sample, in linear-index order.
    std::vector<StaticAccumVoxel> readStaticAccumulator();

  private:
    // Level `level` of `image` as RGBA floats, x fastest (the whole level: every slab, every block).
    std::vector<glm::vec4> readLevel(vk::Image& image, uint32_t level);

    std::optional<UpdateRegions> updateRegions_;
    Aabb contentBounds_;
    ConeClosureBox coneClosure_;
    VoxelRegions regions_;  // empty with `regions` off
    vk::Image regionLabels_;
    const vk::Context& context_;
    const Scene& scene_;  // outlives the grid (the Renderer's GpuScene holds it too)
    uint32_t resolution_ = 0;
    uint32_t mipCount_ = 1;
    glm::vec4 originSize_{0.0f};
    BrickLayout bricks_;
    vk::Buffer brickTable_;
    vk::Image radianceMips_, radianceAtlas_, albedo_, normal_, emission_, bounce_;
    vk::Buffer staticAccum_, dynamicAccum_;
    vk::Sampler sampler_, atlasSampler_;
    Memory memory_;
    bool staticVoxelized_ = false;
    bool sparseMip0_ = true;
    // Voxel cache staged for upload: the cached voxels packed back to back, and one copy region per run of
    // voxels consecutive in the accumulator (it is cleared first, empty voxels need no bytes).
    vk::Buffer staticCache_;
    std::vector<VkBufferCopy> staticCacheRegions_;
};

}  // namespace vct
