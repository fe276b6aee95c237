// The environment map on the GPU (render/environment.h): RGBA32F, every level of its prefiltered chain, for the
// background; and the cones' layers (render/environment_cones.h) as a 3D RGBA32F image, one slice a layer, for
// every cone that leaves the voxel grid. Both are sampled with linear filtering (between texels, levels and
// slices), repeated in u (azimuth) and clamped in v (the poles) and w. Uploaded once, when the renderer is made:
// a map depends on the settings and the scene's sun at t = 0, not on the frame.
#pragma once

#include <vector>

#include "lib/shared.h"
#include "render/environment.h"
#include "render/pass_resources.h"
#include "vk/image.h"
#include "vk/sampler.h"

namespace vct {

// What a pass's resource table binds: the map, the cones' layers and their sampler.
struct EnvironmentSource {
    vk::Image* image = nullptr;
    vk::Image* cones = nullptr;
    VkSampler sampler = VK_NULL_HANDLE;

    // Its rows in a pass's table: the map at the shader's `mapBinding`, the cones' layers at
    // VCT_BINDING_ENVIRONMENT_CONES (lib/environment_sample.glsl).
    void addRows(std::vector<ResourceRow>& rows, uint32_t mapBinding,
                 VkShaderStageFlags stages = VK_SHADER_STAGE_COMPUTE_BIT) const {
        rows.push_back(
            {mapBinding, Resource::image("environment", *image, sampler), Access::Sampled, stages});
        rows.push_back({VCT_BINDING_ENVIRONMENT_CONES, Resource::image("environmentCones", *cones, sampler),
                        Access::Sampled, stages});
    }
};

class GpuEnvironment {
  public:
    // A map wider or taller than the device allows is uploaded from its first level that fits.
    GpuEnvironment(const vk::Context& context, const EnvironmentMap& map);
    EnvironmentSource source() { return {&image_, &cones_, sampler_.handle()}; }

  private:
    vk::Image image_;
    vk::Image cones_;
    vk::Sampler sampler_;
};

}  // namespace vct
