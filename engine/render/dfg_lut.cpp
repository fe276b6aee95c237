#include "render/dfg_lut.h"

#include <cstring>

#include "render/dfg_table.h"
#include "vk/buffer.h"
#include "vk/check.h"

namespace vct {

DfgLut::DfgLut(const vk::Context& context, uint32_t size) : device_(context.device()) {
    // RG32F rather than RG16F: the table is tiny, and full precision keeps 1/E in the energy compensation exact.
    const std::vector<glm::vec2> table = makeDfgTable(size);
    vk::ImageDesc desc;
    desc.width = size;
    desc.height = size;
    desc.format = VK_FORMAT_R32G32_SFLOAT;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    image_ = vk::Image(context, desc);

    const VkDeviceSize bytes = table.size() * sizeof(glm::vec2);
    vk::Buffer staging(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUsage::HostVisible);
    std::memcpy(staging.mapped(), table.data(), bytes);
    context.submitAndWait([&](VkCommandBuffer cmd) {
        image_.use(cmd, vk::ImageAccess::TransferDst);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {size, size, 1};
        vkCmdCopyBufferToImage(cmd, staging.handle(), image_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &region);
        image_.use(cmd, vk::ImageAccess::Sampled);
    });

    // Clamp to edge: n·v = 0 and roughness 0 / 1 lie half a texel outside the texel centres.
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    VK_CHECK(vkCreateSampler(device_, &info, nullptr, &sampler_));
}

DfgLut::~DfgLut() {
    if (sampler_) vkDestroySampler(device_, sampler_, nullptr);
}

}  // namespace vct
