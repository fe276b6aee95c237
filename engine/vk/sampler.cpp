#include "vk/sampler.h"

#include <utility>

#include "vk/check.h"

namespace vct::vk {

Sampler::Sampler(const Context& context, const VkSamplerCreateInfo& info) {
    VK_CHECK(vkCreateSampler(context.device(), &info, nullptr, &sampler_));
    device_ = context.device();
}

Sampler& Sampler::operator=(Sampler&& other) noexcept {
    if (this != &other) {
        reset();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
    }
    return *this;
}

void Sampler::reset() {
    if (sampler_) vkDestroySampler(device_, sampler_, nullptr);
    sampler_ = VK_NULL_HANDLE;
    device_ = VK_NULL_HANDLE;
}

}  // namespace vct::vk
