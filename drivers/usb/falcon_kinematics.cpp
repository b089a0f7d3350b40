// falcon_kinematics.cpp — Stamper's Falcon model: inverse/forward kinematics, Jacobian, J^T F
// (equations and conventions in falcon_kinematics.hpp).
#include "drivers/usb/falcon_kinematics.hpp"

#include <cmath>

namespace contactlab::drivers::falcon {

namespace {

double det3(const Mat3& A) {
    return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
           A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

// A^-1 by the adjugate; false when A is singular relative to its own scale.
bool invert3(const Mat3& A, Mat3& out) {
    const double det = det3(A);
    double scale = 0.0;
    for (const auto& row : A)
        for (double v : row) scale = std::fmax(scale, std::fabs(v));
    if (!std::isfinite(det) || !(scale > 0.0) || std::fabs(det) < 1e-12 * scale * scale * scale) return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // Cofactor of A[j][i] (transposed: the adjugate).
            const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            out[i][j] = (A[r0][c0] * A[r1][c1] - A[r0][c1] * A[r1][c0]) / det;
        }
    return true;
}

// One leg's angles at p: t1 (driven), t2 (knee), t3 (shin); false when p is out of its reach.
struct Leg {
    double t1, t2, t3;
};

bool leg_angles(const FalconGeometry& g, int i, const Vec3& p, Leg& out) {
    const double ca = std::cos(g.leg_azimuth[i]), sa = std::sin(g.leg_azimuth[i]);
    const double u = ca * p.x + sa * p.y - g.r;
    const double v = -sa * p.x + ca * p.y - g.s;
    const double w = p.z;
    const double c3 = (v + g.f) / g.b;
    if (!(std::fabs(c3) <= 1.0)) return false;  // also false for NaN
    const double t3 = std::acos(c3);            // [0, pi]: the Falcon's branch
    const double D = g.d + g.e + g.b * std::sin(t3);
    // The knee (a cos t1, a sin t1) lies at distance D from (u + c, w).
    const double U = u + g.c;
    const double rho = std::hypot(U, w);
    const double K = (U * U + w * w + g.a * g.a - D * D) / (2.0 * g.a);
    if (!(rho > 0.0) || !(std::fabs(K) <= rho)) return false;
    const double t1 = std::atan2(w, U) - std::acos(K / rho);
    const double t2 = std::atan2(w - g.a * std::sin(t1), U - g.a * std::cos(t1));
    out = {t1, t2, t3};
    return true;
}

}  // namespace

const char* to_string(KinStatus s) noexcept {
    switch (s) {
        case KinStatus::ok: return "ok";
        case KinStatus::unreachable: return "unreachable";
        case KinStatus::singular: return "singular";
        case KinStatus::no_convergence: return "no_convergence";
    }
    return "unknown";
}

KinStatus inverse_kinematics(const FalconGeometry& g, const Vec3& p, std::array<double, 3>& theta) noexcept {
    // Behind the plane of the hip axes the legs' equations still have solutions: the mirror
    // assembly through the device's base (thighs folded back past -90 deg, e.g. -189 deg for a
    // grip 11 cm behind it), which the Falcon cannot take. Only the device's side is reachable.
    if (!(p.z > 0.0)) return KinStatus::unreachable;
    std::array<double, 3> t{};
    for (int i = 0; i < 3; ++i) {
        Leg l{};
        if (!leg_angles(g, i, p, l)) return KinStatus::unreachable;
        if (!(l.t1 > kMinThighAngle)) return KinStatus::unreachable;
        t[i] = l.t1;
    }
    theta = t;
    return KinStatus::ok;
}

KinStatus angle_jacobian(const FalconGeometry& g, const Vec3& p, Mat3& M) noexcept {
    for (int i = 0; i < 3; ++i) {
        Leg l{};
        if (!leg_angles(g, i, p, l)) return KinStatus::unreachable;
        // a sin(t2 - t1) dt1 = cos t2 du + cot t3 dv + sin t2 dw, and (du, dv, dw) = R(-az) dp.
        const double s3 = std::sin(l.t3);
        const double den = g.a * std::sin(l.t2 - l.t1) * s3;
        if (!(std::fabs(den) > 1e-9 * g.a)) return KinStatus::singular;
        const double ca = std::cos(g.leg_azimuth[i]), sa = std::sin(g.leg_azimuth[i]);
        const double gu = std::cos(l.t2) * s3, gv = std::cos(l.t3), gw = std::sin(l.t2) * s3;
        M[i] = {(ca * gu - sa * gv) / den, (sa * gu + ca * gv) / den, gw / den};
    }
    return KinStatus::ok;
}

KinStatus jacobian(const FalconGeometry& g, const Vec3& p, Mat3& J) noexcept {
    Mat3 M{};
    if (const KinStatus s = angle_jacobian(g, p, M); s != KinStatus::ok) return s;
    return invert3(M, J) ? KinStatus::ok : KinStatus::singular;
}

namespace {

double max_abs_error(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::fmax(std::fabs(a[0] - b[0]), std::fmax(std::fabs(a[1] - b[1]), std::fabs(a[2] - b[2])));
}

KinStatus newton(const FalconGeometry& g, const std::array<double, 3>& theta, Vec3 x, Vec3& p) {
    std::array<double, 3> t{};
    if (inverse_kinematics(g, x, t) != KinStatus::ok) return KinStatus::unreachable;
    double err = max_abs_error(theta, t);
    for (int it = 0; it < kForwardIterations; ++it) {
        if (err < kForwardTolerance) {
            p = x;
            return KinStatus::ok;
        }
        Mat3 J{};
        if (const KinStatus s = jacobian(g, x, J); s != KinStatus::ok) return s;
        const double e[3] = {theta[0] - t[0], theta[1] - t[1], theta[2] - t[2]};
        double dx[3];
        for (int r = 0; r < 3; ++r) dx[r] = J[r][0] * e[0] + J[r][1] * e[1] + J[r][2] * e[2];
        // Damped step: halve until the new point is reachable and the error shrinks.
        double step = 1.0;
        bool moved = false;
        for (int h = 0; h < 30 && !moved; ++h, step *= 0.5) {
            const Vec3 y{x.x + step * dx[0], x.y + step * dx[1], x.z + step * dx[2]};
            std::array<double, 3> ty{};
            if (inverse_kinematics(g, y, ty) != KinStatus::ok) continue;
            const double ey = max_abs_error(theta, ty);
            if (ey < err || ey < kForwardTolerance) {
                x = y;
                t = ty;
                err = ey;
                moved = true;
            }
        }
        if (!moved) break;
    }
    if (err < kForwardTolerance) {
        p = x;
        return KinStatus::ok;
    }
    return KinStatus::no_convergence;
}

}  // namespace

KinStatus forward_kinematics(const FalconGeometry& g, const std::array<double, 3>& theta, const Vec3& guess,
                             Vec3& p) noexcept {
    for (double t : theta)
        if (!std::isfinite(t)) return KinStatus::unreachable;
    const KinStatus first = newton(g, theta, guess, p);
    if (first == KinStatus::ok) return first;
    // One retry from the device's axis in the middle of the workspace.
    const Vec3 axis{0.0, 0.0, 0.11};
    const KinStatus second = newton(g, theta, axis, p);
    return second == KinStatus::ok ? second : first;
}

KinStatus joint_torques(const FalconGeometry& g, const Vec3& p, const Vec3& f, std::array<double, 3>& tau) noexcept {
    Mat3 J{};
    if (const KinStatus s = jacobian(g, p, J); s != KinStatus::ok) return s;
    // tau = J^T f.
    for (int i = 0; i < 3; ++i) tau[i] = J[0][i] * f.x + J[1][i] * f.y + J[2][i] * f.z;
    return KinStatus::ok;
}

KinStatus grip_force(const FalconGeometry& g, const Vec3& p, const std::array<double, 3>& tau, Vec3& f) noexcept {
    Mat3 M{};
    if (const KinStatus s = angle_jacobian(g, p, M); s != KinStatus::ok) return s;
    // f = M^T tau (J^T M^T = I).
    f.x = M[0][0] * tau[0] + M[1][0] * tau[1] + M[2][0] * tau[2];
    f.y = M[0][1] * tau[0] + M[1][1] * tau[1] + M[2][1] * tau[2];
    f.z = M[0][2] * tau[0] + M[1][2] * tau[1] + M[2][2] * tau[2];
    return KinStatus::ok;
}

double FalconKinematics::theta_of(int arm, std::int32_t counts) const noexcept {
    return g_.theta_at_zero[arm] + kTwoPi * static_cast<double>(counts) / g_.counts_per_rev();
}

double FalconKinematics::counts_exact(int arm, double theta) const noexcept {
    return (theta - g_.theta_at_zero[arm]) / kTwoPi * g_.counts_per_rev();
}

std::int16_t FalconKinematics::counts_of(int arm, double theta) const noexcept {
    const double c = std::round(counts_exact(arm, theta));
    if (std::isnan(c)) return 0;
    return static_cast<std::int16_t>(std::fmax(-32768.0, std::fmin(32767.0, c)));
}

Vec3 planar_force(const FalconPlanarParams& p, Vec2 in_plane, double z) noexcept {
    if (!is_finite(in_plane) || !std::isfinite(z)) return {};
    const double m = glm::length(in_plane);
    if (m > p.max_force) in_plane *= p.max_force / m;  // clamp in N, direction kept
    const double fz = std::fmax(-p.z_max_force, std::fmin(p.z_max_force, -p.z_stiffness * (z - p.z0)));
    return {in_plane.x, in_plane.y, fz};
}

std::array<std::int16_t, 3> motor_counts(const FalconPlanarParams& p, const std::array<double, 3>& tau) noexcept {
    std::array<std::int16_t, 3> out{};
    const double lim = p.motor_max;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(tau[i])) return {};  // never a NaN to the amplifiers: all motors off
        const double c = std::round(tau[i] * p.motor_counts_per_nm);
        out[i] = static_cast<std::int16_t>(std::fmax(-lim, std::fmin(lim, c)));
    }
    return out;
}

}  // namespace contactlab::drivers::falcon
