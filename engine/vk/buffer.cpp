#include "vk/buffer.h"

#include <cstring>
#include <utility>

#include "vk/check.h"

namespace vct::vk {

Buffer::Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory)
    : device_(context.device()), size_(size) {
    // A constructor that throws runs no destructor: free what was made so far here.
    try {
        create(context, usage, memory);
    } catch (...) {
        reset();
        throw;
    }
}

void Buffer::create(const Context& context, VkBufferUsageFlags usage, MemoryUsage memory) {
    const VkDeviceSize size = size_;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &buffer_));

    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device_, buffer_, &requirements);
    VkMemoryPropertyFlags flags =
        memory == MemoryUsage::HostVisible
            ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
            : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = context.memoryType(requirements.memoryTypeBits, flags);
    VK_CHECK(vkAllocateMemory(device_, &alloc, nullptr, &memory_));
    VK_CHECK(vkBindBufferMemory(device_, buffer_, memory_, 0));
    if (memory == MemoryUsage::HostVisible)
        VK_CHECK(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        reset();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(other.size_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
        write_ = std::exchange(other.write_, BufferAccess::None);
        readers_ = std::exchange(other.readers_, BufferAccess::None);
    }
    return *this;
}

void Buffer::reset() {
    if (!device_) return;
    if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
    if (memory_) vkFreeMemory(device_, memory_, nullptr);
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    device_ = VK_NULL_HANDLE;
    write_ = readers_ = BufferAccess::None;
}

Buffer Buffer::withData(const Context& context, const void* data, VkDeviceSize size,
                        VkBufferUsageFlags usage) {
    size = size ? size : 4;  // zero-sized buffers are invalid; keep a placeholder
    Buffer staging(context, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::HostVisible);
    if (data) std::memcpy(staging.mapped(), data, size);
    Buffer buffer(context, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::DeviceLocal);
    context.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, size};
        vkCmdCopyBuffer(cmd, staging.handle(), buffer.handle(), 1, &region);
    });
    return buffer;
}

namespace {

struct StageAccess {
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

StageAccess stageAccess(BufferAccess use) {
    StageAccess s;
    auto add = [&](BufferAccess bit, VkPipelineStageFlags2 stages, VkAccessFlags2 access) {
        if (!any(use & bit)) return;
        s.stages |= stages;
        s.access |= access;
    };
    add(BufferAccess::ShaderRead, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    add(BufferAccess::ShaderWrite, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    add(BufferAccess::IndirectRead, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    add(BufferAccess::TransferRead, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    add(BufferAccess::TransferWrite, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    add(BufferAccess::HostRead, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    return s;
}

}  // namespace

void Buffer::use(VkCommandBuffer cmd, BufferAccess next) {
    BufferAccess waitFor = BufferAccess::None;
    if (any(next & kBufferWrites)) {
        waitFor = write_ | readers_;  // write after write, write after read
        write_ = next;
        readers_ = BufferAccess::None;
    } else {
        // Read after write, for the kinds of read not yet ordered after the last write.
        if (any(next & BufferAccess(~uint32_t(readers_)))) waitFor = write_;
        readers_ = readers_ | next;
    }
    // None on a buffer's first use (host writes before a submission are visible to it) or when nothing is due.
    if (!any(waitFor)) return;
    const StageAccess from = stageAccess(waitFor), to = stageAccess(next);
    VkBufferMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    barrier.srcStageMask = from.stages;
    barrier.srcAccessMask = from.access;
    barrier.dstStageMask = to.stages;
    barrier.dstAccessMask = to.access;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.buffer = buffer_;
    barrier.offset = 0;
    barrier.size = VK_WHOLE_SIZE;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.bufferMemoryBarrierCount = 1;
    dependency.pBufferMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

}  // namespace vct::vk
