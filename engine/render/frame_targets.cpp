#include "render/frame_targets.h"

#include <utility>

#include "core/error.h"
#include "lib/shared.h"

namespace vct {

namespace {

// Target → member, in the table's order.
#define VCT_TARGET_MEMBER_POINTER(name, ...) &FrameTargets::name,
constexpr vk::Image FrameTargets::*kMembers[] = {
    VCT_FRAME_TARGETS(VCT_TARGET_MEMBER_POINTER, VCT_TARGET_MEMBER_POINTER)};
#undef VCT_TARGET_MEMBER_POINTER
static_assert(std::size(kMembers) == kTargetCount);

VkImageUsageFlags usageFlags(TargetUsage usage) {
    // Every target can be sampled and read back (aux images, tests).
    constexpr VkImageUsageFlags always = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    switch (usage) {
        case TargetUsage::Depth:
            return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | always;
        case TargetUsage::Color:
            return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | always;
        case TargetUsage::Storage:
            return VK_IMAGE_USAGE_STORAGE_BIT | always;
    }
    return always;
}

}  // namespace

vk::Image& FrameTargets::image(Target target) {
    return this->*kMembers[size_t(target)];
}
const vk::Image& FrameTargets::image(Target target) const {
    return this->*kMembers[size_t(target)];
}

void FrameTargets::create(const vk::Context& context, uint32_t w, uint32_t h, uint32_t shadowMapSize,
                          uint32_t scale, bool withGi, bool withBlend) {
    width = w;
    height = h;
    traceScale = scale < 1 ? 1 : scale;
    gi = withGi;
    blend = withBlend;
    // Low res rounds up, so every full-res pixel has a low-res sample at or beyond it to filter with.
    const bool upsampled = traceScale > 1;
    const uint32_t lowW = upsampled ? (w + traceScale - 1) / traceScale : 1;
    const uint32_t lowH = upsampled ? (h + traceScale - 1) / traceScale : 1;
    for (size_t i = 0; i < kTargetCount; ++i) {
        const TargetDesc& row = kTargets[i];
        vk::Image& target = image(Target(i));
        if (row.exists == TargetExists::WithGi && !gi) {
            target = vk::Image();
            continue;
        }
        const bool standIn = (row.exists == TargetExists::StandInWithoutGi && !gi) ||
                             (row.exists == TargetExists::StandInWithoutBlend && !blend);
        vk::ImageDesc desc;
        desc.width = standIn                         ? 1
                     : row.size == TargetSize::Frame ? w
                     : row.size == TargetSize::Trace ? lowW
                                                     : shadowMapSize;
        desc.height = standIn                         ? 1
                      : row.size == TargetSize::Frame ? h
                      : row.size == TargetSize::Trace ? lowH
                                                      : shadowMapSize;
        desc.format = row.format;
        desc.usage = usageFlags(row.usage);
        target = vk::Image(context, desc);
    }
    directList = vk::Buffer(context, sizeof(gpu::ResampleListHeader) + VkDeviceSize(w) * h * sizeof(uint32_t),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            vk::MemoryUsage::DeviceLocal);
    if (gi) {
        resampleList =
            vk::Buffer(context, sizeof(gpu::ResampleListHeader) + VkDeviceSize(w) * h * sizeof(uint32_t),
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                           VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                       vk::MemoryUsage::DeviceLocal);
        resampleCount = vk::Buffer(context, sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                   vk::MemoryUsage::HostVisible);
        *static_cast<uint32_t*>(resampleCount.mapped()) = 0;
    } else {
        resampleList = vk::Buffer();
        resampleCount = vk::Buffer();
    }
}

void FrameTargets::swapHistory(bool gbuffer) {
    for (size_t i = 0; i < kTargetCount; ++i) {
        const TargetDesc& row = kTargets[i];
        if (row.historyOf == Target::count || (row.swap == HistorySwap::WithGBuffer && !gbuffer)) continue;
        vk::Image& history = image(Target(i));
        vk::Image& current = image(row.historyOf);
        if (history.valid() && current.valid()) std::swap(history, current);
    }
}

}  // namespace vct
