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

bool PassivityObserver::step(Vec2 x, Vec2 f_prev, double stored, double dt, bool linear) noexcept {
    if (!is_finite(x) || !is_finite(f_prev) || !std::isfinite(stored) || !(dt > 0.0)) {
        reset();
        return false;
    }
    if (primed_) {
        const Vec2 dx = x - prev_x_;
        // Energy delivered to the finger by the held force, plus energy released by the spring:
        // for an ideal continuous spring these cancel; sampling makes their sum positive.
        const double delivered = glm::dot(f_prev, dx);
        const double generated = delivered + (stored - prev_stored_);
        // The device's damping b (N s/m) dissipates b v^2 (W) in every direction, but only the
        // motion along the spring's line of action can pay for what the spring generates: motion
        // across it (sliding, driven by the hand) would credit the loop with dissipation the hand
        // pays for and hide a bounce along the normal (seen at 100 Hz while sliding at 0.19 m/s:
        // -8 mJ of credit against a 1.5 N bounce). So dx is taken along the last force's
        // direction n (kept through free flight between contacts); before any force, whole.
        if (glm::dot(f_prev, f_prev) > 0.0) normal_ = f_prev / glm::length(f_prev);
        const double along = glm::dot(normal_, dx);  // m
        const double dx2 = glm::dot(normal_, normal_) > 0.0 ? along * along : glm::dot(dx, dx);  // m^2
        const double dissipated = p_.device_damping * dx2 / dt;
        const double keep = std::exp(-dt / std::max(p_.leak, dt));
        energy_ = energy_ * keep + generated - dissipated;
        linear_energy_ *= keep;
        if (linear && prev_linear_) linear_energy_ += generated - dissipated;
    }
    prev_x_ = x;
    prev_stored_ = stored;
    prev_linear_ = linear;
    primed_ = true;
    return energy_ > p_.threshold || linear_energy_ > p_.threshold;
}

}  // namespace contactlab
