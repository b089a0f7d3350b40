// plot_history.cpp — rolling columns and period statistics (see plot_history.hpp).
#include "engine/editor/plot_history.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::editor {

void PlotHistory::push(const drivers::TickRecord& r) {
    const float values[kColumns] = {
        static_cast<float>(std::hypot(r.force.x, r.force.y)),
        static_cast<float>(r.depth * 1e3),
        static_cast<float>(r.roller_l * 1e3),
        static_cast<float>(r.l_d * 1e3),
        static_cast<float>((r.roller_target - r.roller_l) * 1e3),
        static_cast<float>(r.period * 1e6),
        static_cast<float>(std::max(0.0, r.observer_used) * 100.0),
    };
    for (int c = 0; c < kColumns; ++c) {
        auto& col = columns_[c];
        // Drop the oldest tenth at once when full: amortised O(1) per push, columns stay contiguous.
        if (col.size() >= capacity_) col.erase(col.begin(), col.begin() + static_cast<long>(capacity_ / 10 + 1));
        col.push_back(values[c]);
    }
}

PlotHistory::PeriodStats PlotHistory::period_stats(double nominal) const {
    PeriodStats s;
    std::vector<float> p = columns_[period_us];
    s.count = p.size();
    if (p.empty()) return s;
    std::sort(p.begin(), p.end());
    auto at = [&](double q) { return 1e-6 * p[std::min(p.size() - 1, static_cast<std::size_t>(q * (p.size() - 1) + 0.5))]; };
    s.p50 = at(0.50);
    s.p99 = at(0.99);
    s.max = 1e-6 * p.back();
    for (float v : p)
        if (1e-6 * v > 1.5 * nominal) ++s.late;
    return s;
}

}  // namespace contactlab::editor
