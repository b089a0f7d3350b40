// spsc_ring.hpp — a bounded single-producer single-consumer ring of trivially copyable items.
//
// The servo thread (producer) pushes one record per tick without locking or allocating; a writer
// thread (consumer) drains it to disk. Capacity is fixed at construction (off the servo thread).
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <type_traits>

namespace contactlab {

template <class T>
class SpscRing {
    static_assert(std::is_trivially_copyable_v<T>);

public:
    // capacity is rounded up to a power of two (>= 2).
    explicit SpscRing(std::size_t capacity) {
        std::size_t c = 2;
        while (c < capacity) c <<= 1;
        mask_ = c - 1;
        items_ = std::make_unique<T[]>(c);
    }

    std::size_t capacity() const { return mask_ + 1; }

    // Producer only. False when full (the caller decides: count a drop, or wait in virtual time).
    bool try_push(const T& v) noexcept {
        const std::size_t head = head_.load(std::memory_order_relaxed);
        if (head - tail_cache_ > mask_) {
            tail_cache_ = tail_.load(std::memory_order_acquire);
            if (head - tail_cache_ > mask_) return false;
        }
        items_[head & mask_] = v;
        head_.store(head + 1, std::memory_order_release);
        return true;
    }

    // Consumer only. False when empty.
    bool try_pop(T& out) noexcept {
        const std::size_t tail = tail_.load(std::memory_order_relaxed);
        if (tail == head_cache_) {
            head_cache_ = head_.load(std::memory_order_acquire);
            if (tail == head_cache_) return false;
        }
        out = items_[tail & mask_];
        tail_.store(tail + 1, std::memory_order_release);
        return true;
    }

    bool empty() const noexcept {
        return head_.load(std::memory_order_acquire) == tail_.load(std::memory_order_acquire);
    }

private:
    std::size_t mask_ = 0;
    std::unique_ptr<T[]> items_;
    alignas(64) std::atomic<std::size_t> head_{0};
    std::size_t tail_cache_ = 0;  // producer's view of tail
    alignas(64) std::atomic<std::size_t> tail_{0};
    std::size_t head_cache_ = 0;  // consumer's view of head
};

}  // namespace contactlab
