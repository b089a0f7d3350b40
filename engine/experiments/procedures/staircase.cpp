// staircase.cpp — 1-up-N-down (staircase.hpp; Levitt 1971).
#include "engine/experiments/procedures/staircase.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::experiments {

Staircase::Staircase(const Procedure& p)
    : p_(p), level_(std::isfinite(p.start) ? p.start : p.hi), step_(std::isfinite(p.step) ? p.step : (p.hi - p.lo) / 8.0) {}

bool Staircase::update(bool correct) {
    ++trials_;
    int move = 0;
    if (correct) {
        if (++run_ >= p_.down) move = -1, run_ = 0;
    } else {
        move = +1, run_ = 0;
    }
    if (move == 0) return false;
    const bool reversal = direction_ != 0 && move != direction_;
    if (reversal) {
        reversal_levels_.push_back(level_);
        if (std::find(p_.halve_at.begin(), p_.halve_at.end(), reversals()) != p_.halve_at.end()) step_ *= 0.5;
    }
    direction_ = move;
    // Clamped to the protocol's range: the device cannot show a negative radius difference,
    // and beyond the largest stimulus nothing is easier.
    level_ = std::clamp(level_ + move * step_, p_.lo, p_.hi);
    return reversal;
}

bool Staircase::finished() const { return reversals() >= p_.reversals || trials_ >= p_.max_trials; }

double Staircase::estimate() const {
    if (reversal_levels_.empty()) return NAN;
    const std::size_t k = std::min<std::size_t>(reversal_levels_.size(), static_cast<std::size_t>(p_.estimate_reversals));
    double sum = 0.0;
    for (std::size_t i = reversal_levels_.size() - k; i < reversal_levels_.size(); ++i) sum += reversal_levels_[i];
    return sum / static_cast<double>(k);
}

}  // namespace contactlab::experiments
