// staircase.hpp — a transformed up-down staircase (Levitt 1971, "Transformed up-down methods
// in psychoacoustics", JASA 49: 467-477): 1-up-N-down. The stimulus falls by one step after N
// correct answers in a row and rises by one step after any wrong answer, so it hovers where a
// fall is as likely as a rise: p^N = 1/2, p = 0.707 for N = 2, 0.794 for N = 3. A reversal is a
// change of direction; the stimulus at each is kept, and the estimate is the mean of the last K
// of them (Levitt's midpoint-averaging: each reversal is a peak or a valley of the track, and
// with an even K as many of each). The step is halved at the reversals the protocol names
// (default 2 and 4): big steps find the region quickly, small ones measure it.
#pragma once

#include "engine/experiments/protocol/protocol.hpp"

#include <vector>

namespace contactlab::experiments {

class Staircase {
public:
    explicit Staircase(const Procedure& p);

    double next() const { return level_; }
    // The answer to a trial at next(); returns whether it made the track reverse.
    bool update(bool correct);
    bool finished() const;
    // Mean of the last `estimate_reversals` reversal levels (all when fewer); NaN before any.
    double estimate() const;
    int trials() const { return trials_; }
    int reversals() const { return static_cast<int>(reversal_levels_.size()); }
    const std::vector<double>& reversal_levels() const { return reversal_levels_; }

private:
    Procedure p_;
    double level_, step_;
    int run_ = 0;        // correct answers in a row since the last move
    int direction_ = 0;  // -1 falling, +1 rising, 0 not moved yet
    int trials_ = 0;
    std::vector<double> reversal_levels_;
};

}  // namespace contactlab::experiments
