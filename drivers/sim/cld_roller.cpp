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


}  // namespace contactlab::drivers::sim
