// safety.cpp — clamp/saturate, ramp-in + fault latch, passivity observer.
#include "haptics/safety.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab {

Vec2 clamp_then_saturate(Vec2 f, double max_force, Vec2 axis_max) noexcept {
    if (!is_finite(f) || !(max_force > 0.0)) return Vec2{0.0};
    const double m = glm::length(f);
    if (m > max_force) f *= max_force / m;
    f.x = std::clamp(f.x, -std::abs(axis_max.x), std::abs(axis_max.x));
    f.y = std::clamp(f.y, -std::abs(axis_max.y), std::abs(axis_max.y));
    return f;
}

const char* to_string(ServoState s) noexcept {
    switch (s) {
        case ServoState::idle: return "idle";
        case ServoState::arming: return "arming";
        case ServoState::ramping: return "ramping";
        case ServoState::engaged: return "engaged";
        case ServoState::fault: return "fault";
    }
    return "?";
}

const char* to_string(ServoFault f) noexcept {
    switch (f) {
        case ServoFault::none: return "none";
        case ServoFault::non_finite_input: return "non-finite device reading";
        case ServoFault::non_finite_output: return "non-finite force";
        case ServoFault::watchdog: return "servo stalled (watchdog)";
        case ServoFault::instability: return "loop unstable (passivity observer)";
        case ServoFault::device: return "device fault";
    }
    return "?";
}

void SafetySupervisor::connect(double t) noexcept {
    if (state_ == ServoState::fault) return;
    state_ = ServoState::ramping;
    since_ = t;
}

void SafetySupervisor::disconnect() noexcept {
    state_ = ServoState::idle;
    fault_ = ServoFault::none;
}

void SafetySupervisor::raise(ServoFault f, double t) noexcept {
    if (state_ != ServoState::fault) {
        fault_ = f;
        ++fault_count_;
    }
    last_fault_ = f;
    state_ = ServoState::fault;
    since_ = t;  // a persisting cause keeps extending the hold
}

double SafetySupervisor::step(double t) noexcept {
    switch (state_) {
        case ServoState::idle: return 0.0;
        case ServoState::fault: {
            const bool latched = fault_ == ServoFault::instability && p_.latch_instability;
            const bool held = t - since_ >= p_.fault_hold;
            if (held && (!latched || clear_requested_)) {
                clear_requested_ = false;
                fault_ = ServoFault::none;
                state_ = ServoState::ramping;
                since_ = t;
            }
            return 0.0;
        }
        case ServoState::arming:  // not entered any more; treated as the start of a ramp
            state_ = ServoState::ramping;
            since_ = t;
            return 0.0;
        case ServoState::ramping: {
            const double s = p_.ramp_time > 0.0 ? (t - since_) / p_.ramp_time : 1.0;
            if (s >= 1.0) {
                state_ = ServoState::engaged;
                return 1.0;
            }
            return std::clamp(s, 0.0, 1.0);
        }
        case ServoState::engaged: return 1.0;
    }
    return 0.0;
}

bool PassivityObserver::step(double generated, double dt, bool linear) noexcept {
    if (!std::isfinite(generated) || !(dt > 0.0)) {
        reset();
        return false;
    }
    const double keep = std::exp(-dt / std::max(p_.leak, dt));
    energy_ = energy_ * keep + generated;
    linear_energy_ *= keep;
    if (linear && prev_linear_) linear_energy_ += generated;
    prev_linear_ = linear;
    return energy_ > p_.threshold || linear_energy_ > p_.threshold;
}

}  // namespace contactlab
