// tick_stats.cpp — percentiles and period misses of the recorded tick times.
#include "engine/bench/tick_stats.hpp"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace contactlab::bench {

std::string printf_text(const char* format, ...) {
    // Measured first, then written: the report's longer paragraphs (the roller tracking's, over
    // 400 characters) were cut at a fixed 256-byte buffer, and the table after one joined its line.
    va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    const int n = std::vsnprintf(nullptr, 0, format, args);
    va_end(args);
    std::string out(n > 0 ? static_cast<std::size_t>(n) : 0, '\0');
    if (n > 0) std::vsnprintf(out.data(), out.size() + 1, format, again);
    va_end(again);
    return out;
}

std::string duration(double ns) {
    // The thresholds sit where %.3g would round up to the next unit (999.95 us is "1.00 ms", not
    // "1e+03 us").
    if (ns < 999.5) return printf_text("%.0f ns", ns);
    if (ns < 999.5e3) return printf_text("%.3g us", ns / 1e3);
    return printf_text("%.3g ms", ns / 1e6);
}

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

std::vector<double> least_over_passes(const std::vector<double>& ns, std::size_t ticks_per_pass) {
    if (ticks_per_pass == 0 || ns.size() % ticks_per_pass != 0)
        throw std::invalid_argument("least_over_passes: " + std::to_string(ns.size()) + " tick times are not whole passes of " +
                                    std::to_string(ticks_per_pass));
    if (ns.empty()) return {};
    std::vector<double> least(ns.begin(), ns.begin() + static_cast<std::ptrdiff_t>(ticks_per_pass));
    for (std::size_t i = ticks_per_pass; i < ns.size(); ++i) {
        double& l = least[i % ticks_per_pass];
        l = std::min(l, ns[i]);
    }
    return least;
}

}  // namespace contactlab::bench
