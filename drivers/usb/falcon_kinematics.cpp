// falcon_kinematics.cpp — rotary delta IK/FK/Jacobian (see falcon_kinematics.hpp).
#include "drivers/usb/falcon_kinematics.hpp"

#include <cmath>

namespace contactlab::drivers::falcon {

namespace {

// Solves A x = b for 3x3 A (Cramer); false when singular.
bool solve3(const double A[3][3], const double b[3], double x[3]) {
    const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                       A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                       A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    if (!std::isfinite(det) || std::fabs(det) < 1e-18) return false;
    for (int c = 0; c < 3; ++c) {
        double M[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) M[i][j] = j == c ? b[i] : A[i][j];
        x[c] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) / det;
    }
    return true;
}

}  // namespace

bool FalconKinematics::inverse(const Vec3& p, std::array<double, 3>& theta) const noexcept {
    const double L = g_.upper, l = g_.lower, r = g_.base - g_.effector;
    for (int i = 0; i < 3; ++i) {
        // The grip in arm i's frame (x' radial, y' tangential, z along the device axis).
        const double c = std::cos(g_.azimuth[i]), s = std::sin(g_.azimuth[i]);
        const double xr = c * p.x + s * p.y, yt = -s * p.x + c * p.y;
        const double dx = xr - r;
        // |A - E|^2 = l^2 with E = (L cos t, L sin t) in the arm's (radial, z) plane gives
        // dx cos t + z sin t = K.
        const double K = (dx * dx + yt * yt + p.z * p.z + L * L - l * l) / (2.0 * L);
        const double rho = std::hypot(dx, p.z);
        if (!(rho > 0.0) || std::fabs(K) > rho) return false;
        // The elbow-out branch (upper arm pointing away from the axis), as the Falcon is built.
        theta[i] = std::atan2(p.z, dx) - std::acos(K / rho);
    }
    return true;
}

bool FalconKinematics::dtheta_dp(const Vec3& p, double M[3][3]) const noexcept {
    constexpr double h = 1e-7;  // m, central differences
    for (int j = 0; j < 3; ++j) {
        Vec3 a = p, b = p;
        (j == 0 ? a.x : j == 1 ? a.y : a.z) += h;
        (j == 0 ? b.x : j == 1 ? b.y : b.z) -= h;
        std::array<double, 3> ta{}, tb{};
        if (!inverse(a, ta) || !inverse(b, tb)) return false;
        for (int i = 0; i < 3; ++i) M[i][j] = (ta[i] - tb[i]) / (2.0 * h);
    }
    return true;
}

bool FalconKinematics::forward(const std::array<double, 3>& theta, const Vec3& guess, Vec3& p) const noexcept {
    Vec3 x = guess;
    for (int it = 0; it < 60; ++it) {
        std::array<double, 3> t{};
        double M[3][3];
        if (!inverse(x, t) || !dtheta_dp(x, M)) return false;
        const double e[3] = {theta[0] - t[0], theta[1] - t[1], theta[2] - t[2]};
        if (std::fabs(e[0]) + std::fabs(e[1]) + std::fabs(e[2]) < 1e-12) {
            p = x;
            return true;
        }
        double d[3];
        if (!solve3(M, e, d)) return false;
        // Halve a step that would leave the reachable set (far corners seen from a central guess).
        double step = 1.0;
        for (int h = 0; h < 20; ++h, step *= 0.5) {
            std::array<double, 3> probe{};
            if (inverse({x.x + step * d[0], x.y + step * d[1], x.z + step * d[2]}, probe)) break;
        }
        x.x += step * d[0];
        x.y += step * d[1];
        x.z += step * d[2];
    }
    std::array<double, 3> t{};
    if (!inverse(x, t)) return false;
    if (std::fabs(t[0] - theta[0]) + std::fabs(t[1] - theta[1]) + std::fabs(t[2] - theta[2]) > 1e-9) return false;
    p = x;
    return true;
}

bool FalconKinematics::torques(const Vec3& p, const Vec3& f, std::array<double, 3>& tau) const noexcept {
    // J = dp/dtheta = M^-1 with M = dtheta/dp, so tau = J^T f solves M^T tau = f.
    double M[3][3], Mt[3][3];
    if (!dtheta_dp(p, M)) return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Mt[i][j] = M[j][i];
    const double b[3] = {f.x, f.y, f.z};
    double x[3];
    if (!solve3(Mt, b, x)) return false;
    tau = {x[0], x[1], x[2]};
    return true;
}

bool FalconKinematics::force(const Vec3& p, const std::array<double, 3>& tau, Vec3& f) const noexcept {
    double M[3][3];
    if (!dtheta_dp(p, M)) return false;
    // f = M^T tau.
    f.x = M[0][0] * tau[0] + M[1][0] * tau[1] + M[2][0] * tau[2];
    f.y = M[0][1] * tau[0] + M[1][1] * tau[1] + M[2][1] * tau[2];
    f.z = M[0][2] * tau[0] + M[1][2] * tau[1] + M[2][2] * tau[2];
    return true;
}

double FalconKinematics::theta_of(int arm, std::int16_t counts) const noexcept {
    return g_.theta_offset[arm] + kTwoPi * counts / g_.counts_per_rev;
}

std::int16_t FalconKinematics::counts_of(int arm, double theta) const noexcept {
    const double c = std::round((theta - g_.theta_offset[arm]) / kTwoPi * g_.counts_per_rev);
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
