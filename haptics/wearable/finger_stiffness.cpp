// finger_stiffness.cpp — eq. 8 of seed 003 (see finger_stiffness.hpp).
#include "haptics/wearable/finger_stiffness.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace contactlab::wearable {

Mat6 finger_stiffness(const FingerStiffnessDef& def) {
    return finger_stiffness_diag(def.k, def.k, def.k_rotation, def.k_rotation);
}

Mat6 finger_stiffness_diag(double k_t, double k_n, double k_b, double k_s) {
    Pose d;
    d << k_t, k_t, k_n, k_b, k_b, k_s;
    return d.asDiagonal();
}

StiffnessCheck check_stiffness(const Mat6& k) {
    if (!k.allFinite()) return {false, "the finger stiffness has a non-finite entry"};
    if ((k - k.transpose()).norm() > 1e-9 * k.norm()) return {false, "the finger stiffness is not symmetric"};
    const Eigen::LLT<Mat6> llt(k);
    if (llt.info() != Eigen::Success) return {false, "the finger stiffness is not positive definite"};
    return {true, {}};
}

Wrench finger_wrench(const Mat6& k, const Pose& rest, const Pose& xi) {
    // w_p = -T^-T K (xi - xi_0)
    const Mat6 t = euler_rate_map(xi);
    return -t.transpose().partialPivLu().solve(k * (xi - rest));
}

Pose compliant_pose(const Mat6& k, const Pose& rest, const Wrench& w_p, const Pose& t_at) {
    // eq. 8: xi = xi_0 - K^-1 T^T w_p
    const Mat6 t = euler_rate_map(t_at);
    return rest - k.llt().solve(t.transpose() * w_p);
}

}  // namespace contactlab::wearable
