// finger_stiffness.hpp — seed 003 §3.5, eq. 8: the fingertip as a linear 6-D spring.
//
//   eq. 8  xi = K^-1 w_p
//
// read about the rest pose xi_0 (the platform touching the pad with zero force) and with the sign
// of statics.hpp's w_p (the fingertip's wrench on the platform): the platform pressed into the pad
// by xi - xi_0 feels w_p = -T^-T K (xi - xi_0), i.e.
//
//   xi - xi_0 = -K^-1 T(xi)^T w_p
//
// where T(xi) maps Euler-angle rates to the twist (platform.hpp), so K acts on the seed's
// coordinates xi = [p; alpha beta gamma] and the moment in S_0 is mapped onto them (T = I at
// zero angles, where the seed's linear model is stated).
//
// Units. The seed takes K = k I with k = 2 N/mm. Read literally in SI the rotational entries would
// be 2000 N m/rad (a platform that cannot tilt); ContactLab reads the seed's k I in millimetres:
// 2 N/mm on translations and 2 N mm/rad = 0.002 N m/rad on rotations. The seed's richer model
// diag(k_t, k_t, k_n, k_b, k_b, k_s) is available through `stiffness` (any symmetric positive
// definite matrix, e.g. from a scene).
#pragma once

#include "haptics/wearable/platform.hpp"

#include <string>

namespace contactlab::wearable {

struct FingerStiffnessDef {
    double k = 2000.0;              // N/m on p_x, p_y, p_z (seed: k = 2 N/mm)
    double k_rotation = 0.002;      // N m/rad on alpha, beta, gamma (seed's k read as N mm/rad)
};

// K = diag(k, k, k, k_rotation, k_rotation, k_rotation).
Mat6 finger_stiffness(const FingerStiffnessDef& def = {});

// The seed's anisotropic model diag(k_t, k_t, k_n, k_b, k_b, k_s) (N/m x3, N m/rad x3).
Mat6 finger_stiffness_diag(double k_t, double k_n, double k_b, double k_s);

// Whether K is usable: finite, symmetric (to 1e-9 relative) and positive definite (Eigen LLT).
struct StiffnessCheck {
    bool ok = false;
    std::string why;
};
StiffnessCheck check_stiffness(const Mat6& k);

// The fingertip's wrench on the platform at pose xi (eq. 8 solved for w_p).
Wrench finger_wrench(const Mat6& k, const Pose& rest, const Pose& xi);

// Eq. 8: the pose at which the fingertip exerts w_p on the platform, given T evaluated at
// `t_at` (the seed's estimation uses the previous step's pose).
Pose compliant_pose(const Mat6& k, const Pose& rest, const Wrench& w_p, const Pose& t_at);

}  // namespace contactlab::wearable
