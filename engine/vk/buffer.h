// A VkBuffer with its own memory. Host-visible buffers stay mapped (per-frame uniforms, readbacks);
// device-local ones are filled once through a staging copy. Like vk::Image, a buffer remembers how it was
// used, so that barriers follow from declared uses (use()) instead of being written by hand.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>

#include "vk/context.h"

namespace vct::vk {

enum class MemoryUsage { DeviceLocal, HostVisible };

// How commands touch a buffer; flags, since one pass may use a buffer several ways at once (the re-trace list
// is an indirect dispatch's arguments, a storage buffer and a copy source in one pass). Shader accesses are
// compute-shader accesses: the graphics passes read only buffers written before the frame (the scene's).
enum class BufferAccess : uint32_t {
    None = 0,
    ShaderRead = 1u << 0,
    ShaderWrite = 1u << 1,
    IndirectRead = 1u << 2,   // indirect dispatch arguments
    TransferRead = 1u << 3,   // copy source
    TransferWrite = 1u << 4,  // copy destination, fill, update
    HostRead = 1u << 5,       // mapped reads once the submission's fence has signalled
};
constexpr BufferAccess operator|(BufferAccess a, BufferAccess b) {
    return BufferAccess(uint32_t(a) | uint32_t(b));
}
constexpr BufferAccess operator&(BufferAccess a, BufferAccess b) {
    return BufferAccess(uint32_t(a) & uint32_t(b));
}
constexpr bool any(BufferAccess a) {
    return a != BufferAccess::None;
}
constexpr BufferAccess kBufferWrites = BufferAccess::ShaderWrite | BufferAccess::TransferWrite;

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

    // Emits the barrier `next` needs after the uses recorded so far: a write waits for the last write and
    // every read since; a read waits for the last write, unless an earlier read of the same kinds already
    // did.
    void use(VkCommandBuffer cmd, BufferAccess next);

  private:
    void create(const Context& context, VkBufferUsageFlags usage, MemoryUsage memory);

    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
    BufferAccess write_ = BufferAccess::None;    // the last use that wrote
    BufferAccess readers_ = BufferAccess::None;  // reads since then (each already ordered after it)
};

}  // namespace vct::vk
