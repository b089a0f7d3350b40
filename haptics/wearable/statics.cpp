// statics.cpp — eqs. 5-6 of seed 003 (see statics.hpp).
#include "haptics/wearable/statics.hpp"

#include <Eigen/QR>

namespace contactlab::wearable {

Wrench platform_wrench(const Mat36& j_l, const Eigen::Vector3d& tension) noexcept {
    return j_l.transpose() * tension;  // eq. 5
}

const char* to_string(StaticsStatus s) noexcept {
    switch (s) {
        case StaticsStatus::ok: return "ok";
        case StaticsStatus::outside_subspace: return "the wrench is outside the reachable subspace (least squares, residual reported)";
        case StaticsStatus::needs_push: return "a cable would have to push (negative tension)";
        case StaticsStatus::rank_deficient: return "the cable Jacobian is rank deficient";
        case StaticsStatus::non_finite: return "non-finite input";
    }
    return "?";
}

CableForces cable_forces(const Mat36& j_l, const Wrench& w_p, const StaticsDef& def) {
    CableForces out;
    if (!j_l.allFinite() || !w_p.allFinite()) return out;
    const Eigen::Matrix<double, 6, 3> jt = j_l.transpose();
    Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix<double, 6, 3>> cod;
    cod.setThreshold(def.rank_threshold);
    cod.compute(jt);
    out.rank = static_cast<int>(cod.rank());
    out.tension = cod.solve(w_p);  // eq. 6: the minimum-norm least-squares solution
    out.residual = w_p - jt * out.tension;
    out.residual_force = out.residual.head<3>().norm();
    out.residual_moment = out.residual.tail<3>().norm();
    if (out.rank < 3)
        out.status = StaticsStatus::rank_deficient;
    else if (out.residual_force > def.force_tolerance || out.residual_moment > def.moment_tolerance)
        out.status = StaticsStatus::outside_subspace;
    else if (out.tension.minCoeff() < 0.0)
        out.status = StaticsStatus::needs_push;
    else
        out.status = StaticsStatus::ok;
    return out;
}

}  // namespace contactlab::wearable
