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
    // Within the platform's reach: the reachable rolls at a press are an interval around 0, so
    // the largest reachable roll toward the asked one is found by bisection on its magnitude.
    // 30 halvings bound it to 0.5 rad / 2^30 (5e-10 rad); inverse kinematics allocates nothing.
    auto reachable = [&](double roll) {
        Pose xi = def.platform.rest;
        xi(2) += out.press;
        xi(3) += roll;
        return inverse_kinematics(def.platform, xi).status == IkStatus::ok;
    };
    if (!reachable(out.roll)) {
        double lo = 0.0, hi = 1.0;  // fractions of the asked roll: lo reachable, hi not
        if (!reachable(0.0)) {
            out.roll = 0.0;
            return out;
        }
        for (int i = 0; i < 30; ++i) {
            const double mid = 0.5 * (lo + hi);
            (reachable(mid * out.roll) ? lo : hi) = mid;
        }
        out.roll *= lo;
    }
    return out;
}

PlatformDisplayState platform_display_state(double fx, double fy, double phi, const PlatformDef& platform,
                                            const Mat6& stiffness, const ContactDisplayDef& def) {
    PlatformDisplayState out;
    out.command = contact_to_platform(fx, fy, phi, def);
    out.pose = platform.rest;
    out.pose(2) += out.command.press;
    out.pose(3) += out.command.roll;
    out.pose(4) += out.command.pitch;
    const IkResult ik = inverse_kinematics(platform, out.pose);
    out.reachable = ik.status == IkStatus::ok;
    if (!out.reachable || !out.command.contact) return out;
    const CableForces cf = cable_forces(jacobian_l(ik), finger_wrench(stiffness, platform.rest, out.pose));  // eqs. 8, 6
    out.statics = cf.status;
    out.tension = cf.tension.cwiseMax(0.0);
    return out;
}

}  // namespace contactlab::wearable
