// equilibrium.hpp — the platform held between elastic cables and the fingertip spring: the pose
// and the tensions for given unstretched cable lengths (what the motors' spools set). This is the
// simulated plant's statics (the platform weighs ~1 g: it is taken massless), not a seed equation;
// at its solution eqs. 5 and 8 hold together:
//
//   J_l^T Q = w_p = -T^-T K (xi - xi_0),   Q_i = k_c max(0, l_i(xi) - lambda_i)
//
// found as the minimum of the potential energy
//
//   U(xi) = 1/2 (xi - xi_0)^T K (xi - xi_0) + sum_i 1/2 k_c max(0, l_i(xi) - lambda_i)^2
//
// by Newton's method and a backtracking line search. The Hessian is K + k_c sum_taut (J_l T)_i^T
// (J_l T)_i plus the cables' geometric stiffness sum_i Q_i d^2 l_i / dxi^2 (in closed form,
// weighted_length_hessian in kinematics.hpp): with the fingertip's soft rotational stiffness (finger_stiffness.hpp)
// that term is as large as K itself, and Gauss-Newton alone crawls. When the full Hessian is not
// positive definite the Gauss-Newton one (always positive definite) is used; a trial pose outside the
// workspace (inverse kinematics fails) counts as infinite energy. A slack cable (l_i <= lambda_i)
// carries no tension: that is a state of the result, not an error.
#pragma once

#include "haptics/wearable/finger_stiffness.hpp"
#include "haptics/wearable/kinematics.hpp"

namespace contactlab::wearable {

struct EquilibriumDef {
    // Cable + FSR stack stiffness along the cable (N/m): a 0.3 mm Dyneema line of ~2 cm in series
    // with the FSR's compression; stiff next to the fingertip's 2000 N/m.
    double cable_stiffness = 20000.0;
    int max_iterations = 60;
    double gradient_tolerance = 1e-10;  // N (and N m), on max |dU/dxi|
};

enum class EquilibriumStatus { ok, not_converged, start_outside_workspace, non_finite };
const char* to_string(EquilibriumStatus s) noexcept;

struct Equilibrium {
    EquilibriumStatus status = EquilibriumStatus::non_finite;
    Pose pose = Pose::Zero();                          // xi (m, rad)
    Eigen::Vector3d tension = Eigen::Vector3d::Zero(); // Q (N)
    std::array<bool, 3> slack{true, true, true};
    int iterations = 0;
    double gradient = 0.0;                             // max |dU/dxi| at the answer
};

// The equilibrium for unstretched lengths `lambda` (m), starting from `guess` (the last one).
Equilibrium solve_equilibrium(const PlatformDef& platform, const Mat6& k, const Eigen::Vector3d& lambda,
                              const Pose& guess, const EquilibriumDef& def = {});

}  // namespace contactlab::wearable
