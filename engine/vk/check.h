// VK_CHECK: turns a failed Vulkan call into a vct::Error naming the call and the result.
#pragma once

#include <vulkan/vulkan.h>

#include <string>

#include "core/error.h"

namespace vct::vk {

const char* resultName(VkResult result);

[[noreturn]] void throwVkError(VkResult result, const char* call);

}  // namespace vct::vk

#define VK_CHECK(call)                                                              \
    do {                                                                            \
        VkResult vct_result_ = (call);                                              \
        if (vct_result_ != VK_SUCCESS) ::vct::vk::throwVkError(vct_result_, #call); \
    } while (0)
