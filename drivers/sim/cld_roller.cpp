// cld_roller.cpp — DC motor + leadscrew + wires (see cld_roller.hpp).
#include "drivers/sim/cld_roller.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::drivers::sim {

void CldRoller::place_at(double l) {
    x_ = xe_ = std::clamp(l, -half_travel(), half_travel());
    v_ = ve_ = 0.0;
    stuck_ = true;
}

void CldRoller::set_voltage(double v) {
    volts_ = std::isfinite(v) ? std::clamp(v, -p_.max_voltage, p_.max_voltage) : 0.0;
}

double CldRoller::measured() const {
    const double step = p_.lead / p_.encoder_counts;  // m per count
    return std::floor(x_ / step + 0.5) * step;
}

void CldRoller::step(double h) {
    const double n = n_;  // rad of motor per m of nut travel
    const double mass = mass_;
    const double current = (volts_ - p_.torque_constant * n * v_) / p_.resistance;
    const double drive = p_.torque_constant * n * current - p_.viscous * v_;  // N
    // Stiction: a resting nut stays put until the drive exceeds the break-away force.
    if (stuck_) {
        if (std::abs(drive) > p_.stiction) stuck_ = false;
    }
    if (!stuck_) {
        const double sign = v_ != 0.0 ? (v_ > 0.0 ? 1.0 : -1.0) : (drive > 0.0 ? 1.0 : -1.0);
        const double v_new = v_ + h * (drive - p_.coulomb * sign) / mass;
        // Velocity reversal through zero with too little drive: the nut sticks.
        if (v_ != 0.0 && v_new * v_ <= 0.0 && std::abs(drive) <= p_.stiction) {
            v_ = 0.0;
            stuck_ = true;
        } else {
            v_ = v_new;
        }
    }
    x_ += v_ * h;
    const double half = half_travel();
    if (x_ > half || x_ < -half) {  // hard stop: inelastic
        x_ = std::clamp(x_, -half, half);
        v_ = 0.0;
        stuck_ = true;
    }
    // Element on the wires: spring-damper to the nut. Semi-implicit Euler.
    const double fw = p_.wire_stiffness * (x_ - xe_) + p_.wire_damping * (v_ - ve_);
    ve_ += h * fw / p_.element_mass;
    xe_ += ve_ * h;
}

}  // namespace contactlab::drivers::sim
