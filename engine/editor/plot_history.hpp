// plot_history.hpp — the last few seconds of servo ticks for the rolling plots, as float columns
// ImGui can plot directly (|F| in N, depth in mm, l and l_d in mm, period in us, the passivity
// observer's budget used in %).
#pragma once

#include "drivers/tick_record.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace contactlab::editor {

class PlotHistory {
public:
    enum Column { force_n, depth_mm, l_mm, l_d_mm, roller_error_mm, period_us, budget_pct, kColumns };

    explicit PlotHistory(std::size_t capacity = 5000) : capacity_(capacity) {
        for (auto& c : columns_) c.reserve(capacity);
    }
    void push(const drivers::TickRecord& r);
    // Values oldest first; size() of them.
    const std::vector<float>& column(Column c) const { return columns_[c]; }
    std::size_t size() const { return columns_[0].size(); }
    std::size_t capacity() const { return capacity_; }
    // Period statistics over the window (s): p50, p99, max; overruns = periods > 1.5 nominal.
    struct PeriodStats {
        double p50 = 0, p99 = 0, max = 0;
        std::size_t late = 0, count = 0;
    };
    PeriodStats period_stats(double nominal) const;

private:
    std::size_t capacity_;
    std::vector<float> columns_[kColumns];
};

}  // namespace contactlab::editor
