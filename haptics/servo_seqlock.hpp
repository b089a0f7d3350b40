// servo_seqlock.hpp — a single-writer, many-reader seqlock for small trivially copyable values.
//
// Used both ways across the servo boundary (DESIGN.md "Threads and safety"): the servo publishes
// its state snapshot to the UI, the UI publishes parameters to the servo. The writer never waits;
// readers retry while a write is in progress. The payload is stored as relaxed atomic words so
// that the concurrent copy is not a data race under the C++ memory model (and TSan agrees).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace contactlab {

template <class T>
class Seqlock {
    static_assert(std::is_trivially_copyable_v<T>, "Seqlock payloads are copied word by word");
    static constexpr std::size_t kWords = (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);

public:
    Seqlock() { store(T{}); }
    explicit Seqlock(const T& v) { store(v); }

    // Single writer only. Wait-free.
    void store(const T& v) noexcept {
        std::array<std::uint64_t, kWords> tmp{};
        std::memcpy(tmp.data(), &v, sizeof(T));
        const std::uint64_t s = seq_.load(std::memory_order_relaxed);
        seq_.store(s + 1, std::memory_order_relaxed);  // odd: write in progress
        std::atomic_thread_fence(std::memory_order_release);
        for (std::size_t i = 0; i < kWords; ++i) words_[i].store(tmp[i], std::memory_order_relaxed);
        seq_.store(s + 2, std::memory_order_release);
    }

    // Any number of readers. Lock-free (retries only while a store is in flight).
    T load() const noexcept {
        std::array<std::uint64_t, kWords> tmp{};
        for (;;) {
            const std::uint64_t s0 = seq_.load(std::memory_order_acquire);
            if (s0 & 1u) continue;
            for (std::size_t i = 0; i < kWords; ++i) tmp[i] = words_[i].load(std::memory_order_relaxed);
            std::atomic_thread_fence(std::memory_order_acquire);
            if (seq_.load(std::memory_order_relaxed) == s0) break;
        }
        T v;
        std::memcpy(static_cast<void*>(&v), tmp.data(), sizeof(T));
        return v;
    }

    // Bumped by two per store: lets a reader tell cheaply whether anything new was published.
    std::uint64_t version() const noexcept { return seq_.load(std::memory_order_acquire); }

private:
    std::atomic<std::uint64_t> seq_{0};
    std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace contactlab
