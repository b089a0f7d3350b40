// kinematics.cpp — eqs. 1-4 of seed 003 and the 3-DoF forward kinematics (see kinematics.hpp).
#include "haptics/wearable/kinematics.hpp"

#include <Eigen/LU>

#include <cmath>

namespace contactlab::wearable {

namespace {
constexpr double min_chord = 1e-9;  // m: shorter and d_i has no direction
}

const char* to_string(IkStatus s) noexcept {
    switch (s) {
        case IkStatus::ok: return "ok";
        case IkStatus::non_finite_pose: return "the pose is not finite";
        case IkStatus::cable_cannot_wrap: return "the chord is at least the finger's diameter 2 R_i (eq. 2 undefined)";
        case IkStatus::zero_chord: return "A_i and B_i coincide (zero chord)";
    }
    return "?";
}

const char* to_string(FkStatus s) noexcept {
    switch (s) {
        case FkStatus::ok: return "ok";
        case FkStatus::ik_failed: return "an iterate left the workspace (inverse kinematics failed)";
        case FkStatus::singular: return "the Jacobian of the actuated freedoms is singular";
        case FkStatus::not_converged: return "Newton's method did not converge";
    }
    return "?";
}

IkResult inverse_kinematics(const PlatformDef& def, const Pose& xi) noexcept {
    IkResult out;
    if (!xi.allFinite()) return out;
    const Eigen::Matrix3d rot = rotation(xi);
    const Vec3 p = xi.head<3>();
    const Vec3 normal = rot.col(2);  // z of S_1
    for (int i = 0; i < 3; ++i) {
        CableGeometry& c = out.cables[i];
        c.r = rot * def.b[i];
        c.b = p + c.r;
        c.d = c.b - def.a[i];
        c.q = c.d.norm();  // eq. 1
        if (!(c.q > min_chord)) {
            out.status = IkStatus::zero_chord;
            out.cable = i;
            return out;
        }
        const double ratio = c.q / (2.0 * def.finger_radius[i]);
        if (!(ratio < 1.0)) {
            out.status = IkStatus::cable_cannot_wrap;
            out.cable = i;
            return out;
        }
        c.s = c.d / c.q;
        c.l = 2.0 * def.finger_radius[i] * std::asin(ratio);  // eq. 2
        c.dl_dq = 1.0 / std::sqrt(1.0 - ratio * ratio);       // d(eq. 2)/dq
        c.cos_theta = std::abs(c.s.dot(normal));                // eq. 7's cos(theta_i)
        out.q(i) = c.q;
        out.l(i) = c.l;
    }
    out.status = IkStatus::ok;
    return out;
}

Mat36 jacobian_p(const IkResult& ik) noexcept {
    Mat36 j = Mat36::Zero();
    if (ik.status != IkStatus::ok) return j;
    for (int i = 0; i < 3; ++i) {
        const CableGeometry& c = ik.cables[i];
        j.block<1, 3>(i, 0) = c.s.transpose();
        j.block<1, 3>(i, 3) = c.r.cross(c.s).transpose();  // eq. 3: s . (omega x r) = omega . (r x s)
    }
    return j;
}

Mat36 jacobian_l(const IkResult& ik) noexcept {
    Mat36 j = jacobian_p(ik);
    for (int i = 0; i < 3; ++i) j.row(i) *= ik.cables[i].dl_dq;  // eq. 4 by the chain rule on eq. 2
    return j;
}

EulerDerivatives::EulerDerivatives(const Pose& xi)
    : rx_(Eigen::AngleAxisd(xi(3), Vec3::UnitX()).toRotationMatrix()),
      ry_(Eigen::AngleAxisd(xi(4), Vec3::UnitY()).toRotationMatrix()),
      rz_(Eigen::AngleAxisd(xi(5), Vec3::UnitZ()).toRotationMatrix()) {}

// Each factor of R = Rz Ry Rx commutes with its own axis' cross product, so the derivative of a
// factor is that factor followed by "axis x".
Eigen::Matrix3d EulerDerivatives::first(const Vec3& v, Vec3 (*second)[3]) const noexcept {
    const Vec3 ex = Vec3::UnitX(), ey = Vec3::UnitY(), ez = Vec3::UnitZ();
    const Vec3 u = rx_ * v;  // Rx v
    const Vec3 ux = ex.cross(u);
    const Vec3 yu = ry_ * u, yux = ry_ * ux;
    const Vec3 ey_yu = ey.cross(yu);
    Eigen::Matrix3d d1;
    d1.col(0) = rz_ * yux;           // d/dalpha
    d1.col(1) = rz_ * ey_yu;         // d/dbeta
    d1.col(2) = ez.cross(rz_ * yu);  // d/dgamma
    if (second) {
        second[0][0] = rz_ * (ry_ * ex.cross(ux));
        second[1][1] = rz_ * ey.cross(ey_yu);
        second[2][2] = ez.cross(Vec3(d1.col(2)));
        second[0][1] = rz_ * ey.cross(yux);
        second[0][2] = ez.cross(Vec3(d1.col(0)));
        second[1][2] = ez.cross(Vec3(d1.col(1)));
    }
    return d1;
}

Mat6 weighted_length_hessian(const PlatformDef& def, const Pose& xi, const IkResult& ik,
                             const Eigen::Vector3d& w) noexcept {
    return weighted_length_hessian(def, EulerDerivatives(xi), ik, w);
}

Mat6 weighted_length_hessian(const PlatformDef& def, const EulerDerivatives& rot, const IkResult& ik,
                             const Eigen::Vector3d& w) noexcept {
    Mat6 h = Mat6::Zero();
    if (ik.status != IkStatus::ok) return h;
    for (int i = 0; i < 3; ++i) {
        if (w(i) == 0.0) continue;  // a slack cable pulls with nothing
        const CableGeometry& c = ik.cables[i];
        // D = dd_i/dxi (3x6): the identity on p, the first derivatives of R b_i (m per rad) on
        // the angles; d2: the second derivatives (m per rad^2).
        Vec3 d2[3][3];
        Mat36 dd;
        dd.block<3, 3>(0, 0) = Eigen::Matrix3d::Identity();
        dd.block<3, 3>(0, 3) = rot.first(def.b[i], d2);
        const Pose g = dd.transpose() * c.s;
        const double ratio = c.q / (2.0 * def.finger_radius[i]);
        const double f1 = c.dl_dq;                                                // dl/dq
        const double f2 = f1 * f1 * f1 * ratio / (2.0 * def.finger_radius[i]);    // d^2 l/dq^2 (1/m)
        Mat6 hi = (f2 - f1 / c.q) * g * g.transpose() + (f1 / c.q) * dd.transpose() * dd;
        for (int j = 0; j < 3; ++j)
            for (int k = j; k < 3; ++k) {
                const double a = f1 * c.s.dot(d2[j][k]);
                hi(3 + j, 3 + k) += a;
                if (k != j) hi(3 + k, 3 + j) += a;
            }
        h += w(i) * hi;
    }
    return h;
}

FkResult forward_kinematics(const PlatformDef& def, const Eigen::Vector3d& l, const Pose& guess,
                            const FkDef& fk) noexcept {
    FkResult out;
    out.xi = guess;
    if (!l.allFinite() || !guess.allFinite()) {
        out.status = FkStatus::ik_failed;
        return out;
    }
    constexpr int actuated[3] = {2, 3, 4};  // p_z, alpha, beta
    for (out.iterations = 0; out.iterations <= fk.max_iterations; ++out.iterations) {
        const IkResult ik = inverse_kinematics(def, out.xi);
        if (ik.status != IkStatus::ok) {
            out.status = FkStatus::ik_failed;
            return out;
        }
        const Eigen::Vector3d err = ik.l - l;
        out.residual = err.cwiseAbs().maxCoeff();
        if (out.residual <= fk.tolerance) {
            out.status = FkStatus::ok;
            return out;
        }
        if (out.iterations == fk.max_iterations) break;
        const Mat36 jxi = jacobian_l(ik) * euler_rate_map(out.xi);  // dl / dxi
        Eigen::Matrix3d a;
        for (int k = 0; k < 3; ++k) a.col(k) = jxi.col(actuated[k]);
        const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
        if (!lu.isInvertible()) {
            out.status = FkStatus::singular;
            return out;
        }
        const Eigen::Vector3d step = lu.solve(err);
        for (int k = 0; k < 3; ++k) out.xi(actuated[k]) -= step(k);
    }
    out.status = FkStatus::not_converged;
    return out;
}

}  // namespace contactlab::wearable
