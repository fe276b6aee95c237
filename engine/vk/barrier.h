// A global memory barrier, for buffers and per-mip image work that sit outside Image::use's tracking.
#pragma once

#include <vulkan/vulkan.h>

namespace vct::vk {

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

}  // namespace vct::vk
