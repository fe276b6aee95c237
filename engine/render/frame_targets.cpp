#include "render/frame_targets.h"

namespace vct {

void FrameTargets::create(const vk::Context& context, uint32_t w, uint32_t h, uint32_t shadowMapSize,
                          uint32_t scale) {
    width = w;
    height = h;
    traceScale = scale < 1 ? 1 : scale;
    auto make = [&](uint32_t iw, uint32_t ih, VkFormat format, VkImageUsageFlags usage) {
        vk::ImageDesc desc;
        desc.width = iw;
        desc.height = ih;
        desc.format = format;
        desc.usage = usage;
        return vk::Image(context, desc);
    };
    constexpr VkImageUsageFlags sampled = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    constexpr VkImageUsageFlags attachment = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | sampled;
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT | sampled;
    shadowMap = make(shadowMapSize, shadowMapSize, kDepthFormat,
                     VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
    depth = make(w, h, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | sampled);
    normalRoughness = make(w, h, kNormalRoughnessFormat, attachment);
    baseColorMetallic = make(w, h, kBaseColorMetallicFormat, attachment);
    emissiveOcclusion = make(w, h, kEmissiveOcclusionFormat, attachment);
    motion = make(w, h, kMotionFormat, attachment);
    direct = make(w, h, kRadianceFormat, storage);
    // Low res rounds up, so that every full-res pixel has a low-res sample at or beyond it to filter with.
    const uint32_t lowW = (w + traceScale - 1) / traceScale, lowH = (h + traceScale - 1) / traceScale;
    diffuseIndirectLow = make(lowW, lowH, kRadianceFormat, storage);
    specularIndirectLow = make(lowW, lowH, kRadianceFormat, storage);
    diffuseIndirect = make(w, h, kRadianceFormat, storage);
    specularIndirect = make(w, h, kRadianceFormat, storage);
    hdr = make(w, h, kHdrFormat, storage);
    ldr = make(w, h, kLdrFormat, storage);
}

}  // namespace vct
