// roller_controller.cpp — discrete PID of seed 000 eq. 2 (see roller_controller.hpp).
#include "haptics/roller_controller.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab {

RollerGains sampled_roller_gains(const RollerGains& g, double dt) noexcept {
    if (!(g.pole > 0.0) || !(g.max_pole_period > 0.0) || !(dt > 0.0) || g.pole * dt <= g.max_pole_period) return g;
    const double s = g.max_pole_period / (g.pole * dt);  // < 1: the pole moved toward the origin
    RollerGains out = g;
    out.kp = g.kp * s * s;
    out.ki = g.ki * s * s * s;
    // Never negative: below p = 1 / (3 tau) the motor's back-EMF alone damps more than needed.
    out.kd = std::max(0.0, g.kd * s - (1.0 - s) * g.back_emf);
    // Kd + back_emf scales by s (see above), and the feed-forward that cancels it with it.
    out.kff = g.kff * s;
    return out;
}

void RollerController::reset(double l) noexcept {
    integral_ = 0.0;
    rate_f_ = 0.0;
    target_rate_f_ = 0.0;
    prev_target_ = std::isfinite(l) ? l : 0.0;
    prev_l_ = std::isfinite(l) ? l : 0.0;
    primed_ = std::isfinite(l);
    drive_ = 0.0;
    saturated_ = false;
}

bool roller_gains_usable(const RollerGains& g) noexcept {
    auto gain = [](double v) { return std::isfinite(v) && v >= 0.0; };
    auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
    return gain(g.kp) && gain(g.ki) && gain(g.kd) && gain(g.kff) && positive(g.d_cutoff_hz) && positive(g.ff_cutoff_hz) && positive(g.max_drive) &&
           gain(g.pole) && positive(g.max_pole_period) && gain(g.back_emf);
}

const RollerController::Derived& RollerController::derived(double dt) noexcept {
    if (!(derived_.valid && derived_.dt == dt)) {
        derived_.usable = roller_gains_usable(gains_);
        derived_.alpha = 1.0 - std::exp(-2.0 * 3.141592653589793 * gains_.d_cutoff_hz * dt);
        derived_.alpha_ff = 1.0 - std::exp(-2.0 * 3.141592653589793 * gains_.ff_cutoff_hz * dt);
        derived_.sampled = sampled_roller_gains(gains_, dt);
        derived_.dt = dt;
        derived_.valid = true;
    }
    return derived_;
}

double RollerController::step(double l_d, double l, double dt) noexcept {
    if (!std::isfinite(l_d) || !std::isfinite(l) || !(dt > 0.0) || !std::isfinite(dt) || !derived(dt).usable) {
        reset(l);
        return 0.0;
    }
    if (!primed_) reset(l);
    target_ = std::clamp(l_d, travel_.min, travel_.max);
    const double e = target_ - l;
    const double target_rate = (target_ - prev_target_) / dt;
    prev_target_ = target_;

    // Derivative on measurement, first-order low-pass (exact discretisation of 1/(tau s + 1)).
    const double raw_rate = (l - prev_l_) / dt;
    prev_l_ = l;
    const Derived& k = derived_;  // made for this dt above
    rate_f_ += k.alpha * (raw_rate - rate_f_);
    // The target's rate has its own, slower filter: it carries the encoders' steps (see ff_cutoff_hz).
    target_rate_f_ += k.alpha_ff * (target_rate - target_rate_f_);

    const RollerGains& g = k.sampled;
    const double umax = std::max(0.0, g.max_drive);
    const double p = g.kp * e;
    const double d = -g.kd * rate_f_ + g.kff * target_rate_f_;
    // Conditional integration: integrate unless the output is saturated and the error would push
    // it further into saturation (the integral cannot wind up while the motor is at its limit).
    const double i_next = integral_ + g.ki * e * dt;
    const double u_try = p + i_next + d;
    const bool winding = (u_try > umax && e > 0.0) || (u_try < -umax && e < 0.0);
    if (!winding) integral_ = std::clamp(i_next, -umax, umax);
    double u = p + integral_ + d;
    saturated_ = std::abs(u) > umax;
    u = std::clamp(u, -umax, umax);
    // Past a travel end, never drive further out (the hard stop would stall the motor).
    if ((l >= travel_.max && u > 0.0) || (l <= travel_.min && u < 0.0)) u = 0.0;
    drive_ = u;
    return u;
}

}  // namespace contactlab
