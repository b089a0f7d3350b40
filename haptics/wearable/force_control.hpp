// force_control.hpp — seed 003 §3.7, Fig. 5: cable force control. The reference tensions Q_r are
// compared with the estimates Q-hat (estimation.hpp, Fig. 4) and a PD per motor gives the motor
// torque tau_m:
//
//   tau_m,i = tau_ff(Q_r,i) + K_p (Q_r,i - Q-hat_i) - K_d dQ-hat_i/dt
//
// Beyond the figure, and why:
// - tau_ff = Q_r r / (N eta) (motor.hpp's holding_torque), the torque that holds Q_r at rest: a
//   PD alone leaves the steady error Q_r / (1 + K_p N eta / r), 3.8 % of Q_r at the default K_p
//   (on top of friction's dead band); with tau_ff only friction is left,
//   |e| <= tau_f / (K_p + r / (N eta)).
// - the derivative acts on the estimate, not on the error: a reference step arriving from the
//   100 Hz link does not kick the motors. It is low-passed (first order, exact discretisation).
// - the output is clamped to the stall torque (the PWM duty cannot exceed 100 %).
//
// Bad input is a state with zero torque, never a NaN: a reference above the motors' stall
// cable force (motor.hpp's stall_cable_force: no motor can hold it) or non-finite, and an
// estimate in fault. A negative reference (a cable cannot push) is clamped to zero and reported.
#pragma once

#include "haptics/wearable/estimation.hpp"
#include "haptics/wearable/motor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace contactlab::wearable {

// Default gains. Table 1's friction (0.02 mN m, 8 % of the stall torque) leaves a dead band
// |e| <= tau_f / (K_p + r / (N eta)); the seed's < 2 % at 0.3 N needs K_p >= 3.2e-3 N m/N, and
// 4e-3 leaves 1.6 %. K_d = 1e-5 N m s/N (with the 40 Hz low-pass) damps the cable-fingertip
// mode (~100 rad/s) at the 1 kHz rate; at Q_r = 0.3 N the torque saturates beyond 0.05 N of error.
struct ForceControlDef {
    double kp = 4.0e-3;        // N m of motor torque per N of tension error (see above)
    double kd = 1.0e-5;        // N m per N/s of the estimated tension's rate
    double d_cutoff_hz = 40.0; // Hz, the derivative's low-pass
    bool feedforward = true;   // add the holding torque of Q_r
    double rate_hz = 1000.0;   // Hz, the PD's rate on the device's microcontroller
    double command_rate_hz = 100.0;  // Hz, Q_r updates over the seed's USB serial link (0.01 s)
};

enum class ControlStatus {
    ok,
    saturated,                 // a torque was clamped to the stall torque
    reference_clamped,         // a negative reference was raised to 0 (cables cannot push)
    fault_above_stall,         // a reference above the stall cable force: zero torque
    fault_non_finite,          // a non-finite reference or gain: zero torque
    fault_estimate,            // the estimate is in fault (estimation.hpp): zero torque
    fault_unreachable_pose,    // position control: IK fails at the reference pose: zero torque
};
const char* to_string(ControlStatus s) noexcept;
inline bool is_fault(ControlStatus s) noexcept { return s >= ControlStatus::fault_above_stall; }

struct ControlOutput {
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // tau_m (N m at the motor shafts)
    ControlStatus status = ControlStatus::ok;
    int cable = -1;                                    // the cable a fault or clamp names
};

// Weight of a new sample in a first-order low-pass at cutoff_hz (Hz) sampled every dt (s): the
// exact discretisation 1 - exp(-2 pi f dt) (both controllers filter their rates with it).
inline double low_pass_weight(double cutoff_hz, double dt) noexcept {
    return 1.0 - std::exp(-2.0 * std::numbers::pi * cutoff_hz * dt);
}
// Sets motor i's torque to tau (N m) clamped to +-stall_torque; the first clamp in an otherwise
// good output marks it saturated, naming the cable.
inline void set_clamped_torque(ControlOutput& out, int i, double tau, double stall_torque) noexcept {
    out.torque(i) = std::clamp(tau, -stall_torque, stall_torque);
    if (out.torque(i) != tau && out.status == ControlStatus::ok) {
        out.status = ControlStatus::saturated;
        out.cable = i;
    }
}

class ForceController {
public:
    ForceController() = default;
    ForceController(const ForceControlDef& def, const MotorDef& motor) : def_(def), motor_(motor) {}

    void reset() noexcept { primed_ = false; rate_f_.setZero(); }
    // One PD tick of period dt (s) on reference Q_r (N) and the current estimate.
    ControlOutput step(const Eigen::Vector3d& reference, const Estimate& estimate, double dt) noexcept;

    const ForceControlDef& def() const noexcept { return def_; }
    const MotorDef& motor() const noexcept { return motor_; }

private:
    ForceControlDef def_;
    MotorDef motor_;
    Eigen::Vector3d prev_ = Eigen::Vector3d::Zero();    // Q-hat last tick (N)
    Eigen::Vector3d rate_f_ = Eigen::Vector3d::Zero();  // filtered dQ-hat/dt (N/s)
    bool primed_ = false;
};

}  // namespace contactlab::wearable
