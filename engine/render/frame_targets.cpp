#include "render/frame_targets.h"

#include <utility>

#include "lib/shared.h"

namespace vct {

void FrameTargets::create(const vk::Context& context, uint32_t w, uint32_t h, uint32_t shadowMapSize,
                          uint32_t scale, bool withGi) {
    width = w;
    height = h;
    traceScale = scale < 1 ? 1 : scale;
    gi = withGi;
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
    // Indirect light (trace, upsample, resample) and its history: only with GI (fixed for a renderer's life).
    if (gi) {
        // Low res rounds up, so every full-res pixel has a low-res sample at or beyond it to filter with.
        const uint32_t lowW = (w + traceScale - 1) / traceScale, lowH = (h + traceScale - 1) / traceScale;
        // At trace scale 1 the trace writes the full-res targets and nothing is upsampled: no low-res image,
        // and 1×1 stand-ins for the guides the trace's scale-1 pipeline never writes (it still declares them).
        const bool upsampled = traceScale > 1;
        indirectLow = upsampled ? make(lowW, lowH, kIndirectFormat, storage) : vk::Image();
        const uint32_t guideW = upsampled ? lowW : 1, guideH = upsampled ? lowH : 1;
        guidePosition = make(guideW, guideH, VK_FORMAT_R32G32B32A32_SFLOAT, storage);
        guideNormal = make(guideW, guideH, VK_FORMAT_R16G16B16A16_SFLOAT, storage);
        guideAxis = make(guideW, guideH, VK_FORMAT_R16G16B16A16_SFLOAT, storage);
        indirect = make(w, h, kIndirectFormat, storage);
        indirectHistory = make(w, h, kIndirectFormat, storage);
        prevDepth = make(w, h, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | sampled);
        prevNormalRoughness = make(w, h, kNormalRoughnessFormat, attachment);
        weightSum = make(w, h, kRadianceFormat, storage);
        resampleList =
            vk::Buffer(context, sizeof(gpu::ResampleListHeader) + VkDeviceSize(w) * h * sizeof(uint32_t),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                           VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                       vk::MemoryUsage::DeviceLocal);
        resampleCount = vk::Buffer(context, sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                   vk::MemoryUsage::HostVisible);
        *static_cast<uint32_t*>(resampleCount.mapped()) = 0;
    } else {
        // Composite's indirect binding (one pipeline for both modes; its shader skips it with GI off): 1×1.
        indirect = make(1, 1, kIndirectFormat, storage);
    }
    hdr = make(w, h, kHdrFormat, storage);
    ldr = make(w, h, kLdrFormat, storage);
}

}  // namespace vct

namespace vct {

void FrameTargets::swapHistory(bool gbuffer) {
    if (!gi) return;
    std::swap(indirect, indirectHistory);
    if (!gbuffer) return;
    std::swap(depth, prevDepth);
    std::swap(normalRoughness, prevNormalRoughness);
}

}  // namespace vct
