// platform.hpp — seed 003's wearable platform: the geometry (Table 2, Fig. 3) and the pose xi.
//
// Two frames (seed §3.1-3.2): S_0 on the static platform on the back of the finger (nail side),
// origin P_0, and S_1 on the mobile platform under the fingerpad, origin P_1 at the centroid of
// its cable points B_i. ContactLab's choice of axes (the seed does not fix them): z of S_0 points
// from the pad toward the nail, so the mobile platform hangs below at p_z < 0 and the cables pull
// it up (+z) into the pad; x across the finger, y along it (toward the fingertip).
//
// The pose is xi = [p_x p_y p_z alpha beta gamma] (seed eq. 8's notation): p = P_1 - P_0 in S_0
// (m) and roll alpha, pitch beta, yaw gamma (rad) with R_1^0 = Rz(gamma) Ry(beta) Rx(alpha).
// Velocities follow the seed's eqs. 3-4: v_p = [p_dot; omega] with omega the angular velocity in
// S_0; euler_rate_map() gives T(xi) with v_p = T(xi) xi_dot.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <string>

namespace contactlab::wearable {

using Vec3 = Eigen::Vector3d;
using Pose = Eigen::Matrix<double, 6, 1>;      // xi: m, m, m, rad, rad, rad
using Twist = Eigen::Matrix<double, 6, 1>;     // v_p = [p_dot (m/s); omega (rad/s)]
using Wrench = Eigen::Matrix<double, 6, 1>;    // [f (N); m (N m) about P_1], in S_0
using Mat36 = Eigen::Matrix<double, 3, 6>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Seed 003 Table 2 with the unstated quantities chosen and documented. Defaults: the seed's
// prototype.
struct PlatformDef {
    // A_i in S_0 (m): Table 2a, -0.8/-1.3, 0.8/-1.3, 0/1.3 cm.
    std::array<Vec3, 3> a{Vec3{-0.008, -0.013, 0.0}, Vec3{0.008, -0.013, 0.0}, Vec3{0.0, 0.013, 0.0}};
    // B_i in S_1 (m): Table 2b (-0.9/-0.6, 0.9/-0.6, 0/0.6 cm) moved by -(0, -0.2) cm so that P_1 is
    // the centroid of the B_i, as §3.1 defines it (Table 2's points have their centroid at
    // y = -0.2 cm). The rest pose puts them back where Table 2 has them. Where P_1 lies matters:
    // the fingertip's rotational stiffness acts about it.
    std::array<Vec3, 3> b{Vec3{-0.009, -0.004, 0.0}, Vec3{0.009, -0.004, 0.0}, Vec3{0.0, 0.008, 0.0}};
    // Finger curvature radius under each cable, R_i (m), seed eq. 2. Not given by the seed: 10 mm,
    // half an index fingertip's width. It must exceed half the chord (q_i < 2 R_i) or the cable
    // cannot lie on the finger.
    std::array<double, 3> finger_radius{0.010, 0.010, 0.010};
    // The rest pose xi_0: the platform touching the pad with zero force (m, rad). The seed gives
    // no height: 15 mm below the static platform, about a fingertip's thickness at the nail;
    // p_y = -2 mm puts the B_i at Table 2's coordinates under S_0.
    Pose rest = (Pose() << 0.0, -0.002, -0.015, 0.0, 0.0, 0.0).finished();
};

// R_1^0 = Rz(gamma) Ry(beta) Rx(alpha).
Eigen::Matrix3d rotation(const Pose& xi);

// T(xi) (6x6) with v_p = T xi_dot: identity on p, and on the angles the map from
// (alpha_dot, beta_dot, gamma_dot) to omega in S_0, columns Rz Ry e_x, Rz e_y, e_z. Singular only
// at pitch +-pi/2, far outside the platform's workspace.
Mat6 euler_rate_map(const Pose& xi);

// Whether the platform can be assembled: every value finite, the A_i and the B_i each a proper
// triangle (not collinear), every R_i positive, and at the rest pose every chord q_i shorter than
// 2 R_i (eq. 2 is defined) and longer than zero. `why` names the first failure, for the user.
struct PlatformCheck {
    bool ok = false;
    std::string why;
};
PlatformCheck check_platform(const PlatformDef& def);

}  // namespace contactlab::wearable
