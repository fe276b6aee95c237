// A VkImage with its memory and views, and the last way it was used, so that barriers follow from how a
// pass declares it uses an image (Image::use with an AccessInfo, below; the passes' resource tables in
// render/pass_resources.h) instead of being written by hand.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "vk/context.h"

namespace vct::vk {

// How a pass touches an image; each maps to one layout, stage set and access mask.
enum class ImageAccess {
    Undefined,
    Sampled,       // texture reads from fragment or compute shaders
    StorageRead,   // imageLoad in compute
    StorageWrite,  // imageStore in compute (contents before are discarded where allowed)
    StorageReadWrite,
    ColorAttachment,
    DepthAttachment,
    TransferSrc,
    TransferDst,
    Present,
};

struct ImageDesc {
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t depth = 1;  // > 1 makes a 3D image
    uint32_t mipLevels = 1;
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    VkImageUsageFlags usage = 0;
};

class Image {
  public:
    Image() = default;
    Image(const Context& context, const ImageDesc& desc);
    ~Image() { reset(); }
    Image(Image&& other) noexcept { *this = std::move(other); }
    Image& operator=(Image&& other) noexcept;
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    VkImageView mipView(uint32_t level) const { return mipViews_.at(level); }
    const ImageDesc& desc() const { return desc_; }
    uint32_t width() const { return desc_.width; }
    uint32_t height() const { return desc_.height; }
    uint32_t depth() const { return desc_.depth; }
    VkFormat format() const { return desc_.format; }
    VkImageAspectFlags aspect() const;
    bool valid() const { return image_ != VK_NULL_HANDLE; }

    // Emits the barrier from the last recorded use to `next` (all mips and layers). A read after a read
    // in the same layout needs no barrier and emits none.
    void use(VkCommandBuffer cmd, ImageAccess next);
    ImageAccess lastAccess() const { return access_; }
    // For code that moved the image's layout itself (e.g. a per-mip blit chain).
    void assumeAccess(ImageAccess access) { access_ = access; }

    void reset();

  private:
    void create(const Context& context);

    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    std::vector<VkImageView> mipViews_;
    ImageDesc desc_;
    ImageAccess access_ = ImageAccess::Undefined;
};

// Layout, stages and access for an ImageAccess (shared with code that writes barriers for sub-ranges).
struct AccessInfo {
    VkImageLayout layout;
    VkPipelineStageFlags2 stages;
    VkAccessFlags2 access;
};
AccessInfo accessInfo(ImageAccess access, bool depth);

bool isDepthFormat(VkFormat format);
uint32_t bytesPerPixel(VkFormat format);

}  // namespace vct::vk
