// The environment map on the GPU (render/environment.h): RGBA32F, every level of its prefiltered chain,
// sampled with linear filtering between texels and levels, repeated in u (azimuth) and clamped in v (the
// poles). Uploaded once, when the renderer is made: a map depends on the settings and the scene's sun at
// t = 0, not on the frame.
#pragma once

#include "render/environment.h"
#include "vk/image.h"
#include "vk/sampler.h"

namespace vct {

// What a pass's resource table binds: the map and its sampler.
struct EnvironmentSource {
    vk::Image* image = nullptr;
    VkSampler sampler = VK_NULL_HANDLE;
};

class GpuEnvironment {
  public:
    // A map wider or taller than the device allows is uploaded from its first level that fits.
    GpuEnvironment(const vk::Context& context, const EnvironmentMap& map);
    EnvironmentSource source() { return {&image_, sampler_.handle()}; }

  private:
    vk::Image image_;
    vk::Sampler sampler_;
};

}  // namespace vct
