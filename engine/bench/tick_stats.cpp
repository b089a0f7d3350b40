// tick_stats.cpp — percentiles and period misses of the recorded tick times.
#include "engine/bench/tick_stats.hpp"

#include <algorithm>

namespace contactlab::bench {

TickStats tick_stats(std::vector<double> v) {
    TickStats s;
    s.ticks = v.size();
    if (v.empty()) return s;
    std::sort(v.begin(), v.end());
    // Nearest rank, clamped to the slowest tick: with fewer than 1,000 ticks p99.9 is the maximum.
    auto rank = [&](std::size_t per_thousand) { return v[std::min(v.size() - 1, v.size() * per_thousand / 1000)]; };
    s.median_ns = v[v.size() / 2];
    s.p99_ns = rank(990);
    s.p999_ns = rank(999);
    s.max_ns = v.back();
    s.over_100us = static_cast<std::size_t>(v.end() - std::upper_bound(v.begin(), v.end(), kTenKilohertzPeriodNs));
    s.over_1ms = static_cast<std::size_t>(v.end() - std::upper_bound(v.begin(), v.end(), kOneKilohertzPeriodNs));
    return s;
}

}  // namespace contactlab::bench
