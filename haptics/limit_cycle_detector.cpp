// limit_cycle_detector.cpp — sustained force oscillation counter (see limit_cycle_detector.hpp).
#include "haptics/limit_cycle_detector.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab {

void LimitCycleDetector::reset() noexcept {
    hi_ = lo_ = 0.0;
    last_turn_t_ = 0.0;
    last_half_ = 0.0;
    last_extreme_ = run_swing_ = 0.0;
    have_extreme_ = false;
    rising_ = 0;
    half_cycles_ = 0;
    primed_ = false;
}

bool LimitCycleDetector::step(double t, double f, double max_force, bool armed) noexcept {
    if (!std::isfinite(t) || !std::isfinite(f) || !std::isfinite(max_force)) {
        reset();
        return false;
    }
    if (!primed_) {
        hi_ = lo_ = f;
        last_turn_t_ = t;
        primed_ = true;
        return false;
    }
    // s: longest half-cycle that still counts; longer gaps mean the oscillation stopped.
    const double max_half = p_.min_frequency > 0.0 ? 0.5 / p_.min_frequency : 0.0;
    const double swing = p_.swing_fraction * max_force;  // N
    if (!(swing > 0.0)) return false;
    hi_ = std::max(hi_, f);
    lo_ = std::min(lo_, f);
    // A turn: the force has come back from the running extreme by at least `swing` (N). Smaller
    // reversals (a count of encoder chatter, the hand's slow push) never count.
    double extreme = 0.0;  // N: the maximum or minimum just passed
    bool turned = false;
    if (rising_ >= 0 && f <= hi_ - swing) {
        turned = true;  // a maximum
        extreme = hi_;
        rising_ = -1;
        hi_ = lo_ = f;
    } else if (rising_ <= 0 && f >= lo_ + swing) {
        turned = true;  // a minimum
        extreme = lo_;
        rising_ = +1;
        hi_ = lo_ = f;
    }
    if (turned) {
        last_half_ = t - last_turn_t_;
        // N: this half-cycle's swing, extreme to extreme (the first one has no previous extreme).
        const double this_swing = have_extreme_ ? std::abs(extreme - last_extreme_) : 0.0;
        last_extreme_ = extreme;
        have_extreme_ = true;
        if (last_half_ > max_half) {
            half_cycles_ = 1;
            run_swing_ = this_swing;
        } else if (this_swing < p_.decay_ratio * run_swing_) {
            // Dying out: a loop below the bound rings down geometrically (its swing falls by
            // exp(-sigma / 2f) a half-cycle, sigma = (1 - K / K_c) b / m), a limit cycle holds its
            // swing. Count again from here, so only an oscillation that keeps its size for the
            // whole run of `cycles` is reported.
            half_cycles_ = 1;
            run_swing_ = this_swing;
        } else {
            ++half_cycles_;
            run_swing_ = std::max(run_swing_, this_swing);
        }
        last_turn_t_ = t;
    } else if (t - last_turn_t_ > max_half) {
        half_cycles_ = 0;  // quiet for longer than half the slowest cycle: not sustained
        have_extreme_ = false;
    }
    return p_.enabled && armed && half_cycles_ >= 2 * p_.cycles;
}

}  // namespace contactlab
