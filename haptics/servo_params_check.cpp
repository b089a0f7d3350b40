// servo_params_check.cpp — range checks for the servo's parameters (servo_params_check.hpp).
#include "haptics/servo_params_check.hpp"

#include "haptics/parameter_limits.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace contactlab {
namespace {

std::string fmt(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// "" if lo <= v <= hi (open at lo when lo_open), else the message naming `what` and its unit.
std::string range(const char* what, double v, double lo, double hi, const char* unit, bool lo_open = false) {
    const bool ok = std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi;
    if (ok) return {};
    return std::string(what) + ": must lie in " + (lo_open ? "(" : "[") + fmt(lo) + ", " + fmt(hi) + "]" +
           (unit[0] ? " " : "") + unit + ", got " + fmt(v);
}

}  // namespace

std::string roller_gains_problem(const RollerGains& g) {
    constexpr double kHuge = 1e30;  // beyond any drive per metre a device could use, still finite
    for (const std::string& p :
         {range("roller.kp", g.kp, 0.0, kHuge, "V/m"), range("roller.ki", g.ki, 0.0, kHuge, "V/(m s)"),
          range("roller.kd", g.kd, 0.0, kHuge, "V s/m"), range("roller.kff", g.kff, 0.0, kHuge, "V s/m"),
          range("roller.d_cutoff_hz", g.d_cutoff_hz, 0.0, 1e6, "Hz", true),
          range("roller.ff_cutoff_hz", g.ff_cutoff_hz, 0.0, 1e6, "Hz", true),
          range("roller.max_drive", g.max_drive, 0.0, 1e3, "V", true),
          range("roller.pole", g.pole, 0.0, 1e7, "rad/s"),
          range("roller.max_pole_period", g.max_pole_period, 0.0, 10.0, "", true),
          range("roller.back_emf", g.back_emf, 0.0, kHuge, "V s/m")})
        if (!p.empty()) return p;
    return {};
}

std::string servo_config_problem(const ServoConfig& c) {
    using namespace limits;
    if (!(std::isfinite(c.period) && c.period >= 1.0 / kMaxServoRate && c.period <= 1.0 / kMinServoRate))
        return "period: must lie in [" + fmt(1.0 / kMaxServoRate) + ", " + fmt(1.0 / kMinServoRate) +
               "] s (" + fmt(kMinServoRate) + " Hz to " + fmt(kMaxServoRate) + " Hz), got " + fmt(c.period);
    for (const std::string& p :
         {range("device_max_force", c.device_max_force, 0.0, kMaxForceLimit, "N", true),
          range("axis_max.x", c.axis_max.x, 0.0, kMaxForceLimit, "N", true),
          range("axis_max.y", c.axis_max.y, 0.0, kMaxForceLimit, "N", true),
          range("device_damping", c.device_damping, 0.0, kMaxDamping, "N s/m"),
          range("roller_travel.min", c.roller_travel.min, -1.0, 1.0, "m"),
          range("roller_travel.max", c.roller_travel.max, -1.0, 1.0, "m")})
        if (!p.empty()) return p;
    if (c.has_roller && !(c.roller_travel.min < c.roller_travel.max))
        return "roller_travel: min (" + fmt(c.roller_travel.min) + " m) must be below max (" +
               fmt(c.roller_travel.max) + " m)";
    return {};
}

std::string servo_params_problem(const ServoParams& p, const ServoConfig& c) {
    using namespace limits;
    for (const std::string& s :
         {range("stiffness", p.stiffness, 0.0, kMaxServoStiffness, "N/m", true),
          range("max_force", p.max_force, 0.0, kMaxForceLimit, "N", true),
          range("stiffness_slew", p.stiffness_slew, 0.0, 1e12, "N/m per s", true),
          range("max_force_slew", p.max_force_slew, 0.0, 1e9, "N per s", true),
          // Up to DBL_MAX: a huge threshold is how a probe turns the energy observer off.
          range("passivity_threshold", p.passivity_threshold, 0.0, std::numeric_limits<double>::max(),
                "x the spring's linear energy", true),
          range("roller_travel", p.roller_travel, 0.0, 1.0, "m (0: the device's whole travel)"),
          range("safety.ramp_time", p.safety.ramp_time, 0.0, 60.0, "s"),
          range("safety.fault_hold", p.safety.fault_hold, 0.0, 60.0, "s"),
          range("safety.watchdog_timeout", p.safety.watchdog_timeout, 0.0, 1.0, "s", true), roller_gains_problem(p.roller)})
        if (!s.empty()) return s;
    // A tick arrives every period: a watchdog shorter than two of them would call every tick a stall.
    if (std::isfinite(c.period) && p.safety.watchdog_timeout < 2.0 * c.period)
        return "safety.watchdog_timeout: " + fmt(p.safety.watchdog_timeout) + " s is shorter than two servo periods (" +
               fmt(2.0 * c.period) + " s at " + fmt(1.0 / c.period) + " Hz); every tick would count as a stall";
    return {};
}

}  // namespace contactlab
