// estimation.hpp — seed 003 §3.6, Fig. 4: cable tensions Q-hat and platform pose xi-hat from the
// three FSR readings F_m, one sample at a time, starting from the previous pose estimate
// (the seed assumes xi(j) ~ xi(j-1) between samples):
//
//   1. read F_m,i(j)
//   2. Q-hat_i = F_m,i / cos(theta_i)              eq. 7 inverted, theta_i at xi-hat(j-1)
//   3. w-hat_p = J_l^T Q-hat                       eq. 5, J_l at xi-hat(j-1)
//   4. xi-hat(j) = xi_0 - K^-1 T^T w-hat_p         eq. 8 (sign: finger_stiffness.hpp)
//   5. inverse kinematics at xi-hat(j): theta-hat_i and l-hat_i (eqs. 1-2), for position control
//
// Solving step 4. Done once per sample, as the seed does (EstimatorMethod::seed_one_pass), the
// update is a fixed-point iteration across samples whose gain is K^-1 times the cables' geometric
// stiffness: with the fingertip's soft rotational stiffness (finger_stiffness.hpp) that gain
// exceeds 1 about the tilt axes and the estimate oscillates between +-1.5 rad on a reading held
// still (tests/haptics/test_wearable_estimation.cpp shows it). The default
// (EstimatorMethod::newton) solves eq. 8 with the tensions of eq. 7 for the pose itself,
//   K (xi - xi_0) + T(xi)^T J_l(xi)^T Q-hat(xi) = 0,  Q-hat_i(xi) = F_m,i / cos(theta_i(xi)),
// by Newton's method from the previous estimate (the residual's Jacobian in closed form,
// Eigen's full-pivot LU): the same fixed point, reached stably.
//
// The sensor model is eq. 7 itself, F_m,i = Q_i cos(theta_i) (fsr_model), as the seed assumes
// (sensors decoupled, forces applied at B_i, finger curvature neglected).
//
// Faults are states with zero tensions and the previous pose kept, never NaN: a reading outside
// the FSR's range, a non-finite reading, a cable (nearly) in the platform's plane (cos(theta_i)
// ~ 0: eq. 7 cannot be inverted), a pose estimate outside the workspace. A cable reading
// (near) zero is reported slack, which is not a fault.
#pragma once

#include "haptics/wearable/finger_stiffness.hpp"
#include "haptics/wearable/kinematics.hpp"

namespace contactlab::wearable {

enum class EstimatorMethod {
    seed_one_pass,  // steps 2-5 once, theta and J_l at the previous estimate (the seed's Fig. 4)
    newton,         // eq. 8 solved for the pose (see above)
};

struct EstimatorDef {
    // Interlink FSR 400: usable to about 10 N in the seed's 5 mm button (N).
    double fsr_max = 10.0;
    // Readings in [fsr_min, 0) are noise around zero and count as 0; below fsr_min the sensor or
    // its wiring is faulty (N).
    double fsr_min = -0.05;
    // Below this |cos(theta_i)| the cable lies (nearly) in the platform's plane: eq. 7 would
    // divide by ~0 (dimensionless; 0.05 is 87 degrees).
    double min_cos_theta = 0.05;
    // A cable whose estimated tension is below this is reported slack (N).
    double slack_tension = 0.005;
    EstimatorMethod method = EstimatorMethod::newton;
    int max_iterations = 30;           // Newton iterations per sample
    double residual_tolerance = 1e-12; // N (and N m), on max |residual|
};

enum class EstimateStatus {
    ok,
    non_finite_reading,
    reading_out_of_range,      // F_m,i outside [fsr_min, fsr_max]
    cable_parallel_to_platform,// |cos(theta_i)| < min_cos_theta at the previous pose
    pose_outside_workspace,    // IK fails at the previous or the new pose
    not_converged,             // Newton's method did not reach the tolerance (pose kept)
};
const char* to_string(EstimateStatus s) noexcept;

struct Estimate {
    EstimateStatus status = EstimateStatus::ok;
    int cable = -1;                                    // the cable a fault names (0..2), else -1
    Eigen::Vector3d tension = Eigen::Vector3d::Zero(); // Q-hat (N); zero on a fault
    Wrench wrench = Wrench::Zero();                    // w-hat_p (N, N m)
    Pose pose = Pose::Zero();                          // xi-hat (m, rad); the previous one on a fault
    Eigen::Vector3d length = Eigen::Vector3d::Zero();  // l-hat (m) at xi-hat
    Eigen::Vector3d cos_theta = Eigen::Vector3d::Ones();
    std::array<bool, 3> slack{false, false, false};
};

// Eq. 7 as a sensor model: the FSR readings (N) for tensions Q (N) at a pose (an ok IK result).
Eigen::Vector3d fsr_model(const IkResult& ik, const Eigen::Vector3d& tension) noexcept;

// What EstimatorMethod::newton drives to zero at pose xi for readings `reading` (N, each >= 0):
// the residual K (xi - xi_0) + T^T J_l^T Q-hat(xi) (N, N m) and its Jacobian in closed form.
// ok is false (both zero) where the pose is outside the workspace or a cable lies in the
// platform's plane.
struct Eq8Residual {
    bool ok = false;
    Pose value = Pose::Zero();
    Mat6 jacobian = Mat6::Zero();
};
Eq8Residual eq8_residual(const EstimatorDef& def, const PlatformDef& platform, const Mat6& k,
                         const Eigen::Vector3d& reading, const Pose& xi);

// One sample of Fig. 4.
Estimate estimate(const EstimatorDef& def, const PlatformDef& platform, const Mat6& k,
                  const Eigen::Vector3d& fsr, const Pose& previous_pose);

}  // namespace contactlab::wearable
