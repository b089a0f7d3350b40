// tick_stats.hpp — per-tick timing: each proxy update timed on its own (steady_clock, ~20 ns of
// overhead included), summarised as median, 99th and 99.9th percentiles and maximum (ns), and the
// ticks that would miss a 10 kHz period (over 100 us) or a 1 kHz period (over 1 ms). A haptic loop
// is judged by its slowest tick: a late tick holds the last force and feeds energy into the device.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::bench {

inline constexpr double kTenKilohertzPeriodNs = 100e3;  // ns: a tick over this misses 10 kHz
inline constexpr double kOneKilohertzPeriodNs = 1e6;    // ns: a tick over this misses 1 kHz

// ns as a readable figure: 950 ns, 1.52 us, 3.10 ms (the report's tables and the goals).
std::string duration(double ns);

// printf into a string, for the report's and the goals' figures and paragraphs (any length).
std::string printf_text(const char* format, ...) __attribute__((format(printf, 1, 2)));

struct TickStats {
    double median_ns = 0.0;
    double p99_ns = 0.0;
    double p999_ns = 0.0;  // 99.9th percentile: the nearest-rank tick 1 in 1,000 reaches
    double max_ns = 0.0;
    std::size_t ticks = 0;
    std::size_t over_100us = 0;  // ticks longer than kTenKilohertzPeriodNs
    std::size_t over_1ms = 0;    // ticks longer than kOneKilohertzPeriodNs
};

// The statistics of a set of tick times (ns), in any order.
TickStats tick_stats(std::vector<double> samples_ns);

// Each tick's least time over the passes of one stroke. `ns` holds whole passes of
// `ticks_per_pass` ticks, pass after pass, as TickTimer records them; the result has one entry
// per tick of a pass. Every pass replays the same samples from the same lifted start, so a tick
// that is slow in every pass is slow by its own work, and one slow in a single pass was slowed by
// the machine (a preemption, an interrupt, caches flushed by another process): the statistics of
// these least times are the code's own tail, to read beside the all-ticks figures a user meets.
// Throws std::invalid_argument when `ticks_per_pass` is 0 or does not divide ns.size().
std::vector<double> least_over_passes(const std::vector<double>& ns, std::size_t ticks_per_pass);

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
    TickStats stats() const { return tick_stats(samples_); }
    // Each tick's time (ns), in the order they ran.
    const std::vector<double>& samples() const { return samples_; }

private:
    std::vector<double> samples_;  // ns
};

}  // namespace contactlab::bench
