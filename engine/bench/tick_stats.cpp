// tick_stats.cpp — percentiles of the recorded tick times.
#include "engine/bench/tick_stats.hpp"

#include <algorithm>

namespace contactlab::bench {

TickStats TickTimer::stats() const {
    TickStats s;
    s.ticks = samples_.size();
    if (samples_.empty()) return s;
    std::vector<double> v = samples_;
    std::sort(v.begin(), v.end());
    s.median_ns = v[v.size() / 2];
    s.p99_ns = v[std::min(v.size() - 1, v.size() * 99 / 100)];
    s.max_ns = v.back();
    return s;
}

}  // namespace contactlab::bench
