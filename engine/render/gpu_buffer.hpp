// gpu_buffer.hpp — a host-visible, host-coherent Vulkan buffer kept mapped (vertex, index and
// readback buffers: small enough that device-local staging is not worth it here).
#pragma once

#include "engine/render/context.hpp"

#include <cstddef>

namespace contactlab::render {

class GpuBuffer {
public:
    GpuBuffer() = default;
    GpuBuffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage);
    ~GpuBuffer() { reset(); }
    GpuBuffer(GpuBuffer&& o) noexcept { *this = std::move(o); }
    GpuBuffer& operator=(GpuBuffer&& o) noexcept;
    GpuBuffer(const GpuBuffer&) = delete;
    GpuBuffer& operator=(const GpuBuffer&) = delete;

    void reset();
    VkBuffer buffer() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* data() const { return mapped_; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

// Grows `buf` (never shrinks) so it holds at least `size` bytes; contents are not kept.
void ensure_buffer(const VulkanContext& ctx, GpuBuffer& buf, VkDeviceSize size, VkBufferUsageFlags usage);

}  // namespace contactlab::render
