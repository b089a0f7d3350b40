// anticipation_spread.hpp — what spreading free-space anticipation over ticks costs in accuracy
// (ProxyDef::anticipation_budget): the same hover stroke through an exact proxy and a spread one,
// side by side, l_d compared on every free tick. The bench's "anticipation spread" table.
#pragma once

#include "engine/bench/cost_scenes.hpp"
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"

#include <vector>

namespace contactlab::bench {

// The budget the bench measures (segments a tick): the smallest of 128/256/512 whose l_d error on
// the 100,000-segment dense hover stayed under a roller encoder step (0.04 mm) on the development
// machine (128: 2 cm at a near tie it reached late; 256: 0.06 mm; 512: 0).
inline constexpr int kBenchAnticipationBudget = 256;

struct SpreadError {
    int free_ticks = 0;
    double l_d_error_p99 = 0.0;  // m, |l_d spread - l_d exact| over the free ticks
    double l_d_error_max = 0.0;  // m
    int behind_max = 0;          // ticks: the oldest answer a free tick showed
    int asked_max = 0;           // segments asked in one tick (the budget plus a leaf's last items)
};

// Replays `path` (one pass from rest at its first sample) through `def` exact and with `budget`.
SpreadError anticipation_spread_error(const Environment& env, const ProxyDef& def, const std::vector<FingerSample>& path,
                                      int budget);

}  // namespace contactlab::bench
