// kinematics.hpp — seed 003 §3.2-3.3: inverse kinematics (eqs. 1-2), the Jacobians J_p and J_l
// (eqs. 3-4) and a forward kinematics for the platform's three actuated degrees of freedom.
//
//   eq. 1  q_i = |d_i|, d_i = b_i - a_i, b_i = p + R_1^0 b_i^1     (chord between A_i and B_i, m)
//   eq. 2  l_i = 2 R_i arcsin(q_i / (2 R_i))                        (cable length on the finger, m)
//   eq. 3  q_dot = J_p v_p, row i = [s_i^T, (r_i x s_i)^T], s_i = d_i / q_i, r_i = R_1^0 b_i^1
//          (from q_dot_i = s_i . (p_dot + omega x r_i))
//   eq. 4  l_dot = J_l v_p, J_l = diag(dl_i/dq_i) J_p, dl/dq = 1 / sqrt(1 - (q / 2R)^2)
//
// Degenerate poses are states, never NaN: a chord as long as the finger's diameter (q_i >= 2 R_i:
// the cable would leave the finger, eq. 2 undefined) or of zero length, and a non-finite pose.
#pragma once

#include "haptics/wearable/platform.hpp"

namespace contactlab::wearable {

enum class IkStatus {
    ok,
    non_finite_pose,   // a NaN or Inf in xi
    cable_cannot_wrap, // q_i >= 2 R_i: eq. 2's arcsin is undefined, the cable leaves the finger
    zero_chord,        // q_i ~ 0: A_i and B_i coincide, the cable has no direction
};
const char* to_string(IkStatus s) noexcept;

// One cable at a pose. All in S_0.
struct CableGeometry {
    Vec3 b = Vec3::Zero();      // B_i (m)
    Vec3 d = Vec3::Zero();      // d_i = B_i - A_i (m)
    Vec3 s = Vec3::Zero();      // d_i / q_i, the chord's direction
    Vec3 r = Vec3::Zero();      // R_1^0 b_i^1, B_i relative to P_1 (m)
    double q = 0.0;             // chord, eq. 1 (m)
    double l = 0.0;             // cable length, eq. 2 (m)
    double dl_dq = 1.0;         // eq. 2 differentiated (dimensionless, >= 1)
    // cos(theta_i) of eq. 7: theta_i is the angle between the platform's normal (z of S_1) and
    // d_i; |cos| so that the sign of the normal's choice does not matter.
    double cos_theta = 1.0;
};

struct IkResult {
    IkStatus status = IkStatus::non_finite_pose;
    int cable = -1;                      // the offending cable (0..2) when status != ok
    std::array<CableGeometry, 3> cables;
    Eigen::Vector3d q = Eigen::Vector3d::Zero();  // chords (m), valid when ok
    Eigen::Vector3d l = Eigen::Vector3d::Zero();  // cable lengths (m), valid when ok
};

// Eqs. 1-2 at pose xi. Never allocates.
IkResult inverse_kinematics(const PlatformDef& def, const Pose& xi) noexcept;

// Eq. 3 (3x6, rows of J_p) and eq. 4 (3x6) from an IK result that is ok (zero otherwise).
Mat36 jacobian_p(const IkResult& ik) noexcept;
Mat36 jacobian_l(const IkResult& ik) noexcept;

// Derivatives of R_1^0 v with respect to the Euler angles (alpha, beta, gamma) for vectors v fixed
// in S_1, from R's three factors at one pose (their sines and cosines taken once for every v).
class EulerDerivatives {
public:
    explicit EulerDerivatives(const Pose& xi);
    // d(R v)/d(angles): one column per angle (m per rad for v in m); with `second`, also the
    // second derivatives second[j][k] for j <= k (m per rad^2).
    Eigen::Matrix3d first(const Vec3& v, Vec3 (*second)[3] = nullptr) const noexcept;

private:
    Eigen::Matrix3d rx_, ry_, rz_;
};

// The cables' geometric stiffness: sum_i w_i d^2 l_i / dxi^2 (6x6, symmetric) at pose xi, from
// its IK result (zero unless ok). With w the tensions Q (N) it is the Hessian of sum_i Q_i l_i(xi)
// with Q held fixed: N/m on p, N on p x angles, N m on the angles. Differentiating eq. 2 twice:
//
//   d^2 l_i = f''(q) g g^T + f'(q) [ D^T (I - s s^T) D / q + sum_c s_c d^2 d_c ],   g = D^T s
//
// with D = dd_i/dxi = [I | dR/dalpha b_i, dR/dbeta b_i, dR/dgamma b_i], f' = dl/dq and
// f'' = f'^3 q / (2 R_i)^2, and the second derivatives of R = Rz Ry Rx taken factor by factor
// (d/dalpha Rx = Rx [e_x]x, ...). Closed form: the plant's Newton solve took it from central
// differences of J_l T, 12 inverse kinematics per iteration (all but 2 % of a wearable study).
Mat6 weighted_length_hessian(const PlatformDef& def, const Pose& xi, const IkResult& ik,
                             const Eigen::Vector3d& w) noexcept;
// The same with R's factors at xi already taken (a caller that needs other derivatives too).
Mat6 weighted_length_hessian(const PlatformDef& def, const EulerDerivatives& rot, const IkResult& ik,
                             const Eigen::Vector3d& w) noexcept;

// Forward kinematics of the actuated freedoms: the pose whose cable lengths are `l` (m), with
// the three freedoms the cables do not set (p_x, p_y, gamma) held at the guess's values, solved
// for (p_z, alpha, beta) by Newton's method on eq. 2 (Eigen's full-pivot LU of the 3x3 block
// of J_l T). `guess` also starts the iteration; the rest pose is a good one.
enum class FkStatus { ok, ik_failed, singular, not_converged };
const char* to_string(FkStatus s) noexcept;
struct FkResult {
    FkStatus status = FkStatus::not_converged;
    Pose xi = Pose::Zero();
    int iterations = 0;
    double residual = 0.0;  // max |l_i(xi) - l_i| (m)
};
struct FkDef {
    int max_iterations = 50;
    double tolerance = 1e-12;  // m, on max |l_i(xi) - l_i|
};
FkResult forward_kinematics(const PlatformDef& def, const Eigen::Vector3d& l, const Pose& guess,
                            const FkDef& fk = {}) noexcept;

}  // namespace contactlab::wearable
