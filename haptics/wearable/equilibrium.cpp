// equilibrium.cpp — the plant's quasi-static platform (see equilibrium.hpp).
#include "haptics/wearable/equilibrium.hpp"

#include <Eigen/Cholesky>

#include <cmath>
#include <limits>

namespace contactlab::wearable {

const char* to_string(EquilibriumStatus s) noexcept {
    switch (s) {
        case EquilibriumStatus::ok: return "ok";
        case EquilibriumStatus::not_converged: return "the equilibrium did not converge";
        case EquilibriumStatus::start_outside_workspace: return "the starting pose is outside the workspace";
        case EquilibriumStatus::non_finite: return "non-finite input";
    }
    return "?";
}

namespace {
struct Eval {
    bool ok = false;
    double energy = 0.0;
    Eigen::Vector3d stretch = Eigen::Vector3d::Zero();  // max(0, l - lambda) (m)
    IkResult ik;
};

Eval evaluate(const PlatformDef& platform, const Mat6& k, const Eigen::Vector3d& lambda, double kc, const Pose& xi) {
    Eval e;
    e.ik = inverse_kinematics(platform, xi);
    if (e.ik.status != IkStatus::ok) return e;
    const Pose dxi = xi - platform.rest;
    e.stretch = (e.ik.l - lambda).cwiseMax(0.0);
    e.energy = 0.5 * dxi.dot(k * dxi) + 0.5 * kc * e.stretch.squaredNorm();
    e.ok = true;
    return e;
}
}  // namespace

Equilibrium solve_equilibrium(const PlatformDef& platform, const Mat6& k, const Eigen::Vector3d& lambda,
                              const Pose& guess, const EquilibriumDef& def) {
    Equilibrium out;
    out.pose = guess;
    if (!lambda.allFinite() || !guess.allFinite() || !k.allFinite()) return out;
    const double kc = def.cable_stiffness;
    Eval cur = evaluate(platform, k, lambda, kc, guess);
    if (!cur.ok) {
        out.status = EquilibriumStatus::start_outside_workspace;
        return out;
    }
    Pose xi = guess;
    out.status = EquilibriumStatus::not_converged;
    for (out.iterations = 0; out.iterations <= def.max_iterations; ++out.iterations) {
        const Mat36 j = jacobian_l(cur.ik) * euler_rate_map(xi);  // dl/dxi
        const Eigen::Vector3d tension = kc * cur.stretch;
        const Pose grad = k * (xi - platform.rest) + j.transpose() * tension;
        out.gradient = grad.cwiseAbs().maxCoeff();
        if (out.gradient <= def.gradient_tolerance) {
            out.status = EquilibriumStatus::ok;
            break;
        }
        if (out.iterations == def.max_iterations) break;
        Mat6 h = k;
        for (int i = 0; i < 3; ++i)
            if (cur.stretch(i) > 0.0) h += kc * j.row(i).transpose() * j.row(i);
        // Geometric stiffness sum_i Q_i d^2 l_i/dxi^2, in closed form (weighted_length_hessian).
        Pose step;
        const Eigen::LLT<Mat6> full(h + weighted_length_hessian(platform, xi, cur.ik, tension));
        if (full.info() == Eigen::Success)
            step = -full.solve(grad);
        else
            step = -h.llt().solve(grad);
        // Backtracking (Armijo) on U.
        double t = 1.0;
        const double slope = grad.dot(step);
        Eval trial;
        // Near the answer the predicted decrease falls below what U's rounding (~eps U) can
        // resolve: take the Newton step as it is (it converges quadratically there).
        if (-slope < 1e-11 * cur.energy) {
            trial = evaluate(platform, k, lambda, kc, xi + step);
            if (!trial.ok) break;
            xi += step;
            cur = trial;
            continue;
        }
        for (int b = 0; b < 40; ++b, t *= 0.5) {
            trial = evaluate(platform, k, lambda, kc, xi + t * step);
            if (trial.ok && trial.energy <= cur.energy + 1e-4 * t * slope) break;
            trial.ok = false;
        }
        if (!trial.ok) break;  // no descent: keep the best pose found, not_converged
        xi += t * step;
        cur = trial;
    }
    out.pose = xi;
    out.tension = kc * cur.stretch;
    for (int i = 0; i < 3; ++i) out.slack[i] = !(cur.stretch(i) > 0.0);
    return out;
}

}  // namespace contactlab::wearable
