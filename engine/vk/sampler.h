// A VkSampler that destroys itself: owners hold these, so that a constructor that throws after making a
// sampler (a bad voxel cache found by the Renderer, a texture the device refuses) leaks nothing.
#pragma once

#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace vct::vk {

class Sampler {
  public:
    Sampler() = default;
    Sampler(const Context& context, const VkSamplerCreateInfo& info);
    ~Sampler() { reset(); }
    Sampler(Sampler&& other) noexcept { *this = std::move(other); }
    Sampler& operator=(Sampler&& other) noexcept;
    Sampler(const Sampler&) = delete;
    Sampler& operator=(const Sampler&) = delete;

    VkSampler handle() const { return sampler_; }
    void reset();

  private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace vct::vk
