// A VkBuffer with its own memory. Host-visible buffers stay mapped (per-frame uniforms, readbacks);
// device-local ones are filled once through a staging copy.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>

#include "vk/context.h"

namespace vct::vk {

enum class MemoryUsage { DeviceLocal, HostVisible };

class Buffer {
  public:
    Buffer() = default;
    Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory);
    ~Buffer() { reset(); }
    Buffer(Buffer&& other) noexcept { *this = std::move(other); }
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    // A device-local buffer holding `data` (uploaded through a temporary staging buffer).
    static Buffer withData(const Context& context, const void* data, VkDeviceSize size,
                           VkBufferUsageFlags usage);

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }  // null for device-local buffers
    void reset();

  private:
    void create(const Context& context, VkBufferUsageFlags usage, MemoryUsage memory);

    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

}  // namespace vct::vk
