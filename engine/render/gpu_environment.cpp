#include "render/gpu_environment.h"

#include <algorithm>
#include <cstring>

#include "render/environment_cones.h"
#include "vk/buffer.h"

namespace vct {

GpuEnvironment::GpuEnvironment(const vk::Context& context, const EnvironmentMap& map) {
    const uint32_t maxSize = context.properties().limits.maxImageDimension2D;
    size_t first = 0;
    while (first + 1 < map.levels.size() && map.widths[first] > maxSize) ++first;
    const size_t levels = map.levels.size() - first;
    vk::ImageDesc desc;
    desc.width = map.widths[first];
    desc.height = map.heights[first];
    desc.mipLevels = uint32_t(levels);
    desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    image_ = vk::Image(context, desc);

    size_t texels = 0;
    for (size_t l = first; l < map.levels.size(); ++l) texels += map.levels[l].size();
    // The cones' layers, one slice each; at least two slices, so that the image is 3D for every map (a constant
    // map has one layer: both slices hold it).
    const EnvironmentConeLayers layers = environmentConeLayers(map);
    const uint32_t slices = std::max(layers.count, 2u);
    vk::ImageDesc conesDesc;
    conesDesc.width = layers.width;
    conesDesc.height = layers.height;
    conesDesc.depth = slices;
    conesDesc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    conesDesc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    cones_ = vk::Image(context, conesDesc);
    const size_t sliceTexels = size_t(layers.width) * layers.height;

    vk::Buffer staging(context, (texels + sliceTexels * slices) * sizeof(glm::vec4),
                       VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::MemoryUsage::HostVisible);
    auto* out = static_cast<glm::vec4*>(staging.mapped());
    std::vector<VkBufferImageCopy> regions;
    size_t offset = 0;
    for (size_t l = first; l < map.levels.size(); ++l) {
        for (size_t i = 0; i < map.levels[l].size(); ++i) out[offset + i] = glm::vec4(map.levels[l][i], 1.0f);
        VkBufferImageCopy region{};
        region.bufferOffset = offset * sizeof(glm::vec4);
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, uint32_t(l - first), 0, 1};
        region.imageExtent = {map.widths[l], map.heights[l], 1};
        regions.push_back(region);
        offset += map.levels[l].size();
    }
    VkBufferImageCopy conesRegion{};
    conesRegion.bufferOffset = offset * sizeof(glm::vec4);
    conesRegion.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    conesRegion.imageExtent = {layers.width, layers.height, slices};
    for (uint32_t slice = 0; slice < slices; ++slice) {
        const size_t from = size_t(std::min(slice, layers.count - 1)) * sliceTexels;
        for (size_t i = 0; i < sliceTexels; ++i)
            out[offset + slice * sliceTexels + i] = glm::vec4(layers.texels[from + i], 1.0f);
    }
    context.submitAndWait([&](VkCommandBuffer cmd) {
        image_.use(cmd, vk::ImageAccess::TransferDst);
        vkCmdCopyBufferToImage(cmd, staging.handle(), image_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               uint32_t(regions.size()), regions.data());
        image_.use(cmd, vk::ImageAccess::Sampled);
        cones_.use(cmd, vk::ImageAccess::TransferDst);
        vkCmdCopyBufferToImage(cmd, staging.handle(), cones_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                               1, &conesRegion);
        cones_.use(cmd, vk::ImageAccess::Sampled);
    });

    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    info.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;  // azimuth wraps around
    info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.maxLod = VK_LOD_CLAMP_NONE;
    sampler_ = vk::Sampler(context, info);
}

}  // namespace vct
