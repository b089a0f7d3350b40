// contact_display.cpp — a 2-D contact force as a platform pose (see contact_display.hpp).
#include "haptics/wearable/contact_display.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace contactlab::wearable {

PlatformPoseCommand contact_to_platform(double fx, double fy, double phi, const ContactDisplayDef& def) noexcept {
    PlatformPoseCommand out;
    const double f = std::hypot(fx, fy);
    if (!std::isfinite(f) || !std::isfinite(phi) || !(f >= def.min_force)) return out;
    out.contact = true;
    out.roll = std::remainder(std::atan2(fy, fx) - (phi + 0.5 * std::numbers::pi), 2.0 * std::numbers::pi);
    out.roll = std::clamp(out.roll, -def.max_tilt, def.max_tilt);
    out.press = std::min(f / def.normal_stiffness, def.max_press);
    return out;
}

}  // namespace contactlab::wearable
