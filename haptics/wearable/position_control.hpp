// position_control.hpp — seed 003 §3.7, Fig. 6: platform position control. The reference pose
// xi_r goes through the inverse kinematics (eqs. 1-2) to reference cable lengths l_r; the
// estimated lengths l-hat come from the pose estimate xi-hat (estimation.hpp, Fig. 4: the cables
// are not measured); a PD per motor drives the error:
//
//   tau_m,i = tau_hold(Q-hat_i) + K_p (l-hat_i - l_r,i) + K_d d(l-hat_i - l_r,i)/dt
//
// (a cable longer than its reference is reeled in: positive torque). Beyond the figure, and why:
// - tau_hold = Q-hat r / (N eta), the torque that holds the estimated tension: without it the PD
//   must carry the whole load and leaves an error of Q r / (N eta K_p) (39 um at 0.3 N, 4 % of a
//   1 mm travel); with it only friction's dead band tau_f / K_p (17 um) is left.
// - a slack cable (Q-hat below the estimator's slack threshold) that the error would pay out
//   further gets zero torque: the estimate cannot see a slack cable's length (no force, no
//   compliance), so paying out would run the spool away. A pose the fingertip does not resist
//   (below the rest pose) thus leaves the cables slack and the platform at rest.
// - the derivative of the error is low-passed like force control's; the output is clamped to
//   the stall torque.
// A reference pose outside the workspace (IK fails) or non-finite, and an estimate in fault, give
// zero torque and a fault state.
#pragma once

#include "haptics/wearable/force_control.hpp"

namespace contactlab::wearable {

// Default gains: force control's scaled by the stiffness one cable sees at the rest pose, about
// 300 N/m (the fingertip's 2 N/mm shared by three cables through dl/dq ~ 1.6).
struct PositionControlDef {
    double kp = 1.2;           // N m of motor torque per m of cable-length error
    double kd = 3.0e-3;        // N m per m/s
    double d_cutoff_hz = 40.0; // Hz
    bool hold_tension = true;  // add the holding torque of the estimated tension
    // Take p_x, p_y and gamma of the IK target from the estimate (the fingertip sets them, the
    // cables cannot): l_r then puts p_z, roll and pitch where xi_r asks. Off: the seed's Fig. 6
    // literally, IK of xi_r, and the fingertip's shear under the cables' lateral pull tilts the
    // platform away from xi_r (0.037 for 0.03 rad of roll in tests/haptics).
    bool free_from_estimate = true;
    double rate_hz = 1000.0;   // Hz
    double command_rate_hz = 100.0;  // Hz, xi_r updates over the link
};

class PositionController {
public:
    PositionController() = default;
    PositionController(const PositionControlDef& def, const MotorDef& motor, const PlatformDef& platform,
                       double slack_tension)
        : def_(def), motor_(motor), platform_(platform), slack_tension_(slack_tension) {}

    void reset() noexcept { primed_ = false; rate_f_.setZero(); }
    // One PD tick of period dt (s) toward pose xi_r (m, rad).
    ControlOutput step(const Pose& reference, const Estimate& estimate, double dt) noexcept;

    const Eigen::Vector3d& reference_lengths() const noexcept { return lr_; }  // l_r (m)

private:
    PositionControlDef def_;
    MotorDef motor_;
    PlatformDef platform_;
    double slack_tension_ = 0.005;  // N
    Eigen::Vector3d lr_ = Eigen::Vector3d::Zero();
    Eigen::Vector3d prev_ = Eigen::Vector3d::Zero();    // error last tick (m)
    Eigen::Vector3d rate_f_ = Eigen::Vector3d::Zero();  // filtered error rate (m/s)
    bool primed_ = false;
};

}  // namespace contactlab::wearable
