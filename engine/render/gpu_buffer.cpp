// gpu_buffer.cpp — buffer + memory + persistent mapping.
#include "engine/render/gpu_buffer.hpp"

#include "engine/render/vk_check.hpp"

#include <utility>

namespace contactlab::render {

GpuBuffer::GpuBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage)
    : device_(ctx.device()), size_(size) {
    // Buffer, then host-visible coherent memory bound to it, mapped for its whole life.
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    vk_check(vkCreateBuffer(device_, &info, nullptr, &buffer_), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, buffer_, &req);
    VkMemoryAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = ctx.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                    VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    try {
        vk_check(vkAllocateMemory(device_, &alloc, nullptr, &memory_), "vkAllocateMemory");
        vk_check(vkBindBufferMemory(device_, buffer_, memory_, 0), "vkBindBufferMemory");
        vk_check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
    } catch (...) {
        reset();
        throw;
    }
}

GpuBuffer& GpuBuffer::operator=(GpuBuffer&& o) noexcept {
    if (this != &o) {
        reset();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(o.size_, 0);
        mapped_ = std::exchange(o.mapped_, nullptr);
    }
    return *this;
}

void GpuBuffer::reset() {
    if (!device_) return;
    if (memory_) {
        if (mapped_) vkUnmapMemory(device_, memory_);
        vkFreeMemory(device_, memory_, nullptr);
    }
    if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    size_ = 0;
}

void ensure_buffer(const VulkanContext& ctx, GpuBuffer& buf, VkDeviceSize size, VkBufferUsageFlags usage) {
    if (buf.buffer() && buf.size() >= size) return;
    VkDeviceSize grown = 64 * 1024;
    while (grown < size) grown *= 2;
    buf = GpuBuffer(ctx, grown, usage);
}

}  // namespace contactlab::render
