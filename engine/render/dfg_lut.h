// The split-sum DFG table (render/dfg_table.h) on the GPU: an RG32F size×size texture, sampled with a linear
// clamp-to-edge sampler at uv = (n·v, perceptual roughness) → (scale, bias); see brdf.glsl's specularDfg.
#pragma once

#include "vk/context.h"
#include "vk/image.h"

namespace vct {

class DfgLut {
  public:
    // 32² texels are enough: the table is smooth, and linear filtering interpolates it well (< 1e-2 error).
    explicit DfgLut(const vk::Context& context, uint32_t size = 32);
    ~DfgLut();
    DfgLut(const DfgLut&) = delete;
    DfgLut& operator=(const DfgLut&) = delete;

    vk::Image& image() { return image_; }
    VkSampler sampler() const { return sampler_; }

  private:
    VkDevice device_ = VK_NULL_HANDLE;
    vk::Image image_;
    VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace vct
