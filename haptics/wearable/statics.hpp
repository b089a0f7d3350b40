// statics.hpp — seed 003 §3.4: the platform's statics by virtual work.
//
//   eq. 5  w_p = J_l^T Q          the wrench w_p on the platform that the cable tensions Q (N)
//                                 balance: with l_dot = J_l v_p, tensions doing work -Q . l_dot
//                                 exert -J_l^T Q, so w_p is what the fingertip exerts on the
//                                 platform (N, N m about P_1, in S_0) at equilibrium.
//   eq. 6  Q = (J_l^T)^# w_p      the tensions for a wrench, by the pseudoinverse.
//
// J_l^T is 6x3: only a 3-D subspace of wrenches is reachable. A wrench outside it gets the
// least-squares tensions and its residual w_p - J_l^T Q, reported; a negative tension (a cable
// would have to push) and a rank-deficient J_l are states, not NaNs. The pseudoinverse is
// Eigen's CompleteOrthogonalDecomposition (rank-revealing).
#pragma once

#include "haptics/wearable/kinematics.hpp"

namespace contactlab::wearable {

// Eq. 5.
Wrench platform_wrench(const Mat36& j_l, const Eigen::Vector3d& tension) noexcept;

enum class StaticsStatus {
    ok,                // w_p is reachable (residual within tolerance) and every Q_i >= 0
    outside_subspace,  // least-squares answer: |residual| above tolerance
    needs_push,        // some Q_i < 0: a cable cannot push, the wrench needs it
    rank_deficient,    // J_l has rank < 3 (e.g. two cables parallel): the minimum-norm answer
    non_finite,        // NaN/Inf in the input; Q = 0
};
const char* to_string(StaticsStatus s) noexcept;

struct CableForces {
    StaticsStatus status = StaticsStatus::non_finite;
    Eigen::Vector3d tension = Eigen::Vector3d::Zero();  // Q (N), eq. 6
    Wrench residual = Wrench::Zero();                   // w_p - J_l^T Q (N, N m)
    double residual_force = 0.0;                        // |residual force| (N)
    double residual_moment = 0.0;                       // |residual moment| (N m)
    int rank = 0;                                       // rank of J_l^T
};

struct StaticsDef {
    // Reachability tolerances: a residual within these is rounding, not a missing direction.
    double force_tolerance = 1e-9;   // N
    double moment_tolerance = 1e-11; // N m (a force tolerance times ~1 cm)
    // Relative threshold below which a singular value of J_l^T counts as zero.
    double rank_threshold = 1e-9;
};

// Eq. 6. With needs_push the least-squares tensions are kept (the caller decides whether to clamp).
// Several conditions at once: rank_deficient, then outside_subspace, then needs_push is reported.
CableForces cable_forces(const Mat36& j_l, const Wrench& w_p, const StaticsDef& def = {});

}  // namespace contactlab::wearable
