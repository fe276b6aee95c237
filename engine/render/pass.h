// What every pass sees: a Pass declares its resources once, in a table (render/pass_resources.h) from which
// its pipeline layout, barriers and descriptor writes follow, and records its work in execute(). The runner
// (Renderer) times each pass with a GPU timestamp scope.
#pragma once

#include <vector>

#include "render/frame_targets.h"
#include "render/gpu_scene.h"
#include "render/pass_resources.h"
#include "render/settings.h"
#include "vk/context.h"
#include "vk/image.h"

namespace vct {

// Samplers shared by the screen-space passes.
struct Samplers {
    VkSampler linearClamp = VK_NULL_HANDLE;
    VkSampler nearestClamp = VK_NULL_HANDLE;
    VkSampler shadowCompare = VK_NULL_HANDLE;  // depth comparison (PCF) for the shadow map
};

struct FrameContext {
    const vk::Context& context;
    VkCommandBuffer cmd;
    const GpuScene& scene;
    FrameTargets& targets;
    VkBuffer frameUniforms;
    const RenderSettings& settings;
    const Samplers& samplers;
    const gpu::FrameUniforms& uniforms;  // what the frame uniform buffer holds (the camera: blend's ordering)
};

enum class PassReuse {
    Never,                // runs every frame (the jittered trace and what follows it)
    WhileSceneUnchanged,  // depends only on the scene's geometry and lights (shadow map, voxel grid)
    WhileViewUnchanged,   // depends on those and the camera (G-buffer, direct light)
    // Runs while the scene changes and for a set number of frames after (`--bounces all`'s gathers, converging)
    WhileVoxelLightSettled,
};

class Pass {
  public:
    virtual ~Pass() = default;
    virtual const char* name() const = 0;
    // Records the pass's work, its resource table's barriers first (ResourceTable::bind or barriers).
    virtual void execute(const FrameContext& frame) = 0;
    // What the pass's output depends on, so that the runner can skip it in frames where that did not change
    // (its output persists from the frame that made it): "a pass that has nothing to do" does not run.
    virtual PassReuse reuse() const { return PassReuse::Never; }
    // Called instead of execute() in a frame the runner skips the pass in (its output kept as it is), for passes
    // that report what the last frame recomputed.
    virtual void skipped() {}
};

// Dispatch size for a full-image compute pass in VCT_TILE_SIZE tiles.
inline uint32_t tileCount(uint32_t pixels) {
    return (pixels + VCT_TILE_SIZE - 1) / VCT_TILE_SIZE;
}

// Dispatch size along one axis for a compute pass over voxels (or voxel texels) in VCT_VOXEL_TILE tiles.
inline uint32_t voxelTileCount(uint32_t voxels) {
    return (voxels + VCT_VOXEL_TILE - 1) / VCT_VOXEL_TILE;
}

}  // namespace vct
