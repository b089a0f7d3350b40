// estimation.cpp — seed 003 Fig. 4 (see estimation.hpp).
#include "haptics/wearable/estimation.hpp"

#include <Eigen/LU>

#include <cmath>

namespace contactlab::wearable {

const char* to_string(EstimateStatus s) noexcept {
    switch (s) {
        case EstimateStatus::ok: return "ok";
        case EstimateStatus::non_finite_reading: return "an FSR reading is not finite";
        case EstimateStatus::reading_out_of_range: return "an FSR reading is outside the sensor's range";
        case EstimateStatus::cable_parallel_to_platform: return "a cable lies in the platform's plane (eq. 7 cannot be inverted)";
        case EstimateStatus::pose_outside_workspace: return "the pose estimate left the workspace";
        case EstimateStatus::not_converged: return "the pose estimate did not converge";
    }
    return "?";
}

Eigen::Vector3d fsr_model(const IkResult& ik, const Eigen::Vector3d& tension) noexcept {
    Eigen::Vector3d f;
    for (int i = 0; i < 3; ++i) f(i) = tension(i) * ik.cables[i].cos_theta;  // eq. 7
    return f;
}

namespace {
// Steps 2-3 at pose xi: Q-hat (eq. 7) and w-hat (eq. 5); the status names a degenerate pose.
struct Step {
    EstimateStatus status = EstimateStatus::ok;
    int cable = -1;
    IkResult ik;
    Eigen::Vector3d tension = Eigen::Vector3d::Zero();
    Wrench wrench = Wrench::Zero();
};
Step tensions_at(const EstimatorDef& def, const PlatformDef& platform, const Eigen::Vector3d& reading, const Pose& xi) {
    Step s;
    s.ik = inverse_kinematics(platform, xi);
    if (s.ik.status != IkStatus::ok) {
        s.status = EstimateStatus::pose_outside_workspace;
        s.cable = s.ik.cable;
        return s;
    }
    for (int i = 0; i < 3; ++i) {
        const double c = s.ik.cables[i].cos_theta;
        if (c < def.min_cos_theta) {
            s.status = EstimateStatus::cable_parallel_to_platform;
            s.cable = i;
            return s;
        }
        s.tension(i) = reading(i) / c;  // step 2, eq. 7
    }
    s.wrench = jacobian_l(s.ik).transpose() * s.tension;  // step 3, eq. 5
    return s;
}

// What Newton drives to zero: K (xi - xi_0) + T(xi)^T w-hat(xi) (N, N m), with `at` the step at xi.
Pose residual(const PlatformDef& platform, const Mat6& k, const Pose& xi, const Step& at) {
    return k * (xi - platform.rest) + euler_rate_map(xi).transpose() * at.wrench;
}

// d/dxi of the residual K (xi - xi_0) + sum_i Q-hat_i(xi) dl_i/dxi, in closed form:
//   K + sum_i Q-hat_i d^2 l_i/dxi^2 + sum_i (dl_i/dxi) (dQ-hat_i/dxi)^T,
//   dQ-hat_i/dxi = -(Q-hat_i / cos theta_i) d cos theta_i/dxi,
//   d(s_i . n)/dxi = (n - (s_i . n) s_i)^T D_i / q_i + s_i^T dn/dxi,
// n = R_1^0 e_z the platform's normal and D_i = dd_i/dxi (kinematics.hpp). It was central
// differences, 12 inverse kinematics an iteration: a quarter of a simulated wearable study.
Mat6 residual_jacobian(const PlatformDef& platform, const Mat6& k, const Pose& xi, const Step& at) {
    const EulerDerivatives rot(xi);  // one set of the angles' sines and cosines for every derivative
    Mat6 jac = k + weighted_length_hessian(platform, rot, at.ik, at.tension);
    const Mat36 grad_l = jacobian_l(at.ik) * euler_rate_map(xi);  // row i: dl_i/dxi
    const Vec3 n = rotation(xi).col(2);
    const Eigen::Matrix3d dn = rot.first(Vec3::UnitZ());  // dn/d(angles)
    for (int i = 0; i < 3; ++i) {
        const CableGeometry& c = at.ik.cables[i];
        const double sn = c.s.dot(n);  // +-cos theta_i
        Pose dsn;
        const Vec3 across = (n - sn * c.s) / c.q;  // d(s . n)/dd (1/m)
        dsn.head<3>() = across;
        dsn.tail<3>() = rot.first(platform.b[i]).transpose() * across + dn.transpose() * c.s;
        const Pose dq = -(at.tension(i) / c.cos_theta) * (sn < 0.0 ? -dsn : dsn);  // dQ-hat_i/dxi (N per m or rad)
        jac += grad_l.row(i).transpose() * dq.transpose();
    }
    return jac;
}
}  // namespace

Eq8Residual eq8_residual(const EstimatorDef& def, const PlatformDef& platform, const Mat6& k,
                         const Eigen::Vector3d& reading, const Pose& xi) {
    Eq8Residual out;
    const Step at = tensions_at(def, platform, reading, xi);
    if (at.status != EstimateStatus::ok) return out;
    out.ok = true;
    out.value = residual(platform, k, xi, at);
    out.jacobian = residual_jacobian(platform, k, xi, at);
    return out;
}

Estimate estimate(const EstimatorDef& def, const PlatformDef& platform, const Mat6& k,
                  const Eigen::Vector3d& fsr, const Pose& previous_pose) {
    Estimate out;
    out.pose = previous_pose;
    auto fault = [&](EstimateStatus s, int cable) {
        out.status = s;
        out.cable = cable;
        out.tension.setZero();
        out.wrench.setZero();
        out.pose = previous_pose;
        return out;
    };
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(fsr(i))) return fault(EstimateStatus::non_finite_reading, i);
        if (fsr(i) < def.fsr_min || fsr(i) > def.fsr_max) return fault(EstimateStatus::reading_out_of_range, i);
    }
    if (!previous_pose.allFinite()) return fault(EstimateStatus::pose_outside_workspace, -1);
    const Eigen::Vector3d reading = fsr.cwiseMax(0.0);  // [fsr_min, 0): noise about zero
    Step at = tensions_at(def, platform, reading, previous_pose);
    if (at.status != EstimateStatus::ok) return fault(at.status, at.cable);
    Pose xi = previous_pose;
    if (def.method == EstimatorMethod::seed_one_pass) {
        xi = compliant_pose(k, platform.rest, at.wrench, xi);  // step 4, eq. 8 at the previous pose
    } else {
        // K (xi - xi_0) + T^T w-hat(xi) = 0 by Newton's method.
        bool converged = false;
        for (int it = 0; it < def.max_iterations; ++it) {
            const Pose r = residual(platform, k, xi, at);
            if (r.cwiseAbs().maxCoeff() <= def.residual_tolerance) {
                converged = true;
                break;
            }
            const Eigen::FullPivLU<Mat6> lu(residual_jacobian(platform, k, xi, at));
            if (!lu.isInvertible()) return fault(EstimateStatus::not_converged, -1);
            const Pose step = -lu.solve(r);
            // Halve a step that leaves the workspace or does not reduce the residual.
            double t = 1.0;
            Step next;
            for (int b = 0; b < 30; ++b, t *= 0.5) {
                next = tensions_at(def, platform, reading, xi + t * step);
                if (next.status == EstimateStatus::ok &&
                    residual(platform, k, xi + t * step, next).norm() < (1.0 - 1e-4 * t) * r.norm())
                    break;
                next.status = EstimateStatus::not_converged;
            }
            if (next.status != EstimateStatus::ok) break;
            xi += t * step;
            at = next;
        }
        if (!converged && residual(platform, k, xi, at).cwiseAbs().maxCoeff() > 1e3 * def.residual_tolerance)
            return fault(EstimateStatus::not_converged, -1);
    }
    // Step 5: the inverse kinematics at xi-hat, and Q-hat, w-hat there.
    const Step fin = tensions_at(def, platform, reading, xi);
    if (fin.status != EstimateStatus::ok) return fault(fin.status, fin.cable);
    out.pose = xi;
    out.length = fin.ik.l;
    if (def.method == EstimatorMethod::seed_one_pass) {
        out.tension = at.tension;  // the seed's Q-hat: theta at the previous pose
        out.wrench = at.wrench;
    } else {
        out.tension = fin.tension;
        out.wrench = fin.wrench;
    }
    for (int i = 0; i < 3; ++i) {
        out.cos_theta(i) = fin.ik.cables[i].cos_theta;
        out.slack[i] = out.tension(i) < def.slack_tension;
    }
    return out;
}

}  // namespace contactlab::wearable
