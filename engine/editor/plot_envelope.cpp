// plot_envelope.cpp — per-column min/max and round ticks (see plot_envelope.hpp).
#include "engine/editor/plot_envelope.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::editor {

std::vector<ColumnRange> column_envelope(const std::vector<float>& values, int columns) {
    std::vector<ColumnRange> out(static_cast<std::size_t>(std::max(0, columns)));
    const std::size_t n = values.size();
    if (n == 0 || columns <= 0) return out;
    bool have_prev = false;
    float prev = 0.0f;
    for (std::size_t i = 0; i < n; ++i) {
        const float v = values[i];
        if (!std::isfinite(v)) continue;
        // Value i sits at (i + 1) / n of the width: the newest one at the right edge.
        const auto col = std::min<std::size_t>(static_cast<std::size_t>(columns) - 1,
                                               (i * static_cast<std::size_t>(columns)) / n);
        ColumnRange& c = out[col];
        if (c.empty) {
            c.lo = c.hi = have_prev ? prev : v;  // joined to the value before the column
            c.empty = false;
        }
        c.lo = std::min(c.lo, v);
        c.hi = std::max(c.hi, v);
        prev = v;
        have_prev = true;
    }
    return out;
}

void value_range(const std::vector<float>& values, float& lo, float& hi) {
    bool any = false;
    for (float v : values) {
        if (!std::isfinite(v)) continue;
        if (!any) lo = hi = v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        any = true;
    }
    if (!any) {
        lo = 0.0f;
        hi = 1.0f;
        return;
    }
    const float min_span = std::max(1e-6f, 1e-6f * std::max(std::abs(lo), std::abs(hi)));
    if (hi - lo < min_span) {
        lo -= 0.5f * min_span;
        hi += 0.5f * min_span;
    }
}

std::vector<double> nice_ticks(double lo, double hi, int max_ticks) {
    std::vector<double> ticks;
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || max_ticks < 2) return ticks;
    const double raw = (hi - lo) / (max_ticks - 1);
    // The ladder 1, 2, 5 x 10^k: the smallest step >= raw, then smaller ones while fewer than two
    // round values fall inside (912..1088 us: 100 gives only 1000, 50 gives 950, 1000, 1050).
    double decade = std::pow(10.0, std::floor(std::log10(raw)));
    int k = 0;  // index into {1, 2, 5}
    const double mult[3] = {1.0, 2.0, 5.0};
    while (mult[k] * decade < raw) {
        if (++k == 3) {
            k = 0;
            decade *= 10.0;
        }
    }
    for (int tries = 0; tries < 6; ++tries) {
        const double step = mult[k] * decade;
        ticks.clear();
        for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step)
            ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
        if (ticks.size() >= 2) break;
        if (--k < 0) {
            k = 2;
            decade /= 10.0;
        }
    }
    if (ticks.size() < 2) ticks = {lo, hi};  // a span narrower than one step: its ends
    return ticks;
}

}  // namespace contactlab::editor
