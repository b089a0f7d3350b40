// tick_stats.hpp — per-tick timing: each proxy update timed on its own (steady_clock, ~20 ns of
// overhead included), summarised as median, 99th percentile and maximum (ns).
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

namespace contactlab::bench {

struct TickStats {
    double median_ns = 0.0;
    double p99_ns = 0.0;
    double max_ns = 0.0;
    std::size_t ticks = 0;
};

class TickTimer {
public:
    explicit TickTimer(std::size_t expected_ticks) { samples_.reserve(expected_ticks); }
    // Times f() and records it.
    template <typename F>
    void time(F&& f) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        const auto t1 = std::chrono::steady_clock::now();
        samples_.push_back(static_cast<double>(std::chrono::duration_cast<std::chrono::nanoseconds>(t1 - t0).count()));
    }
    TickStats stats() const;

private:
    std::vector<double> samples_;  // ns
};

}  // namespace contactlab::bench
