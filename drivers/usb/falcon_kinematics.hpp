// falcon_kinematics.hpp — the Novint Falcon's kinematics: R. E. Stamper's model of a three-legged
// parallel (delta-like) mechanism with the Falcon constants libnifalcon publishes, in SI units.
//
// Frame (the published model's): origin on the device's axis in the plane of the three hip axes;
// x right and y up as the user sees the Falcon's face, z along the device axis toward the user
// (the grip sits at z of about 0.075..0.175 m). Right handed.
//
// Leg i (i = 0 top, 1 right, 2 lower left, clockwise from the top as the user sees it) lives in
// its own frame (u, v, w): the device frame rotated by -leg_azimuth[i] about z, then shifted by
// (-r, -s, 0):  u =  cos(az) x + sin(az) y - r,  v = -sin(az) x + cos(az) y - s,  w = z.
// Its three angles (rad) satisfy
//     u = a cos(t1) - c + D cos(t2),   v = b cos(t3) - f,   w = a sin(t1) + D sin(t2),
//     D = d + e + b sin(t3),
// where t1 is the driven thigh angle (the one the encoder reads, increasing as the grip moves
// out along +z), t2 the knee angle and t3 the angle of the shin parallelogram. Inverse kinematics
// is closed form: t3 = acos((v + f) / b) in [0, pi], then t1 from the circle of radius D around
// the knee: (u + c) cos t1 + w sin t1 = K, the branch t1 = atan2(w, u + c) - acos(K / rho) (the
// one the Falcon is built in). Differentiating the three equations and eliminating dt2, dt3:
//     a sin(t2 - t1) dt1 = cos(t2) du + cot(t3) dv + sin(t2) dw,
// which gives the analytic Jacobian M = dtheta/dp row by row; J = dp/dtheta = M^-1 and arm
// torques are tau = J^T F (solve M^T tau = F).
//
// Forward kinematics has no closed form: Newton's method on the inverse kinematics with the
// analytic M, warm-started from a guess (the last pose), step halved when it would leave the
// reachable set or not reduce the error; at most kForwardIterations iterations, converged when
// every arm's angle error is below kForwardTolerance rad. If the guess fails, one retry from the
// device's axis. A failure is a named KinStatus and leaves the output untouched: never a NaN.
//
// Encoders (the published model's "angle from encoder"): the encoder wheel has 320 slots (x4
// quadrature) on a 14.25 mm motor shaft that drives the arm's 110 mm drum, so one arm turn is
// 4 x 320 x 110 / 14.25 = 9880.7 counts, and t1 = 35 deg at count 0 (the homing reference):
//     t1 = theta_at_zero + 2 pi E / counts_per_rev.
//
// Planar use (DESIGN.md "Devices"): the plane of the scene is the device's x-y plane at depth
// z0; the out-of-plane axis gets a restoring spring (as seed 000 holds its arm's base joint), so
// the finger stays in the plane the servo renders.
#pragma once

#include "drivers/device.hpp"

#include <array>

namespace contactlab::drivers::falcon {

struct Vec3 {
    double x = 0.0, y = 0.0, z = 0.0;
};

inline constexpr double kDegree = 0.017453292519943295;  // rad per degree

// The geometry, with the published Falcon constants as defaults (Stamper's symbols). Everything a
// user may calibrate against a unit: lengths, leg azimuths, encoder scale and zero angles.
struct FalconGeometry {
    double a = 0.060;       // m: thigh, hip axis to knee
    double b = 0.1025;      // m: shin parallelogram side
    double c = 0.014;       // m: shin-to-grip offset, u component
    double d = 0.01125;     // m: shin to grip connection joint
    double e = 0.01125;     // m: knee to shin connection joint
    double f = -0.025;      // m: shin-to-grip offset, v component
    double r = 0.037233758; // m: device axis to hip, u component
    double s = -0.027330909;// m: device axis to hip, v component
    std::array<double, 3> leg_azimuth{105.0 * kDegree, -15.0 * kDegree, -135.0 * kDegree};  // rad, from +x toward +y
    double encoder_slots = 320.0;     // slots on the encoder wheel (4 counts each, quadrature)
    double shaft_diameter = 0.01425;  // m: motor shaft (capstan)
    double drum_diameter = 0.110;     // m: the arm's drum the shaft drives
    std::array<double, 3> theta_at_zero{35.0 * kDegree, 35.0 * kDegree, 35.0 * kDegree};  // rad: t1 at count 0

    // Encoder counts per arm revolution: 4 x slots x drum / shaft (9880.7 by default).
    double counts_per_rev() const noexcept { return 4.0 * encoder_slots * drum_diameter / shaft_diameter; }
};

enum class KinStatus {
    ok,
    unreachable,     // no leg configuration reaches the point (or the angles name no point)
    singular,        // at a singular pose: the Jacobian cannot be inverted
    no_convergence,  // forward kinematics did not meet the tolerance in its iterations
};
const char* to_string(KinStatus s) noexcept;

using Mat3 = std::array<std::array<double, 3>, 3>;  // row-major

inline constexpr int kForwardIterations = 50;
inline constexpr double kForwardTolerance = 1e-13;  // rad, max over the arms

// The device's side of its base: a thigh folded back past this (rad) from the plane of the hip
// axes is the legs' mirror solution through the base, not a pose the Falcon can take. Over its
// workspace (+-6 cm across, 7.5..17.5 cm out) the thighs stay within -57..124 deg.
inline constexpr double kMinThighAngle = -90.0 * kDegree;

// Driven angles t1 (rad) of the three legs that put the grip at p (m); unreachable for a point
// no leg configuration reaches, for one on or behind the plane of the hip axes (z <= 0), and for
// a solution with a thigh folded past kMinThighAngle (the mirror assembly through the base).
KinStatus inverse_kinematics(const FalconGeometry& g, const Vec3& p, std::array<double, 3>& theta) noexcept;
// M = dtheta/dp (rad/m) at p, analytic; singular when a row's denominator vanishes.
KinStatus angle_jacobian(const FalconGeometry& g, const Vec3& p, Mat3& M) noexcept;
// J = dp/dtheta (m/rad) at p: the inverse of angle_jacobian.
KinStatus jacobian(const FalconGeometry& g, const Vec3& p, Mat3& J) noexcept;
// Grip position p (m) for driven angles theta (rad), Newton from `guess` (see the top).
KinStatus forward_kinematics(const FalconGeometry& g, const std::array<double, 3>& theta, const Vec3& guess,
                             Vec3& p) noexcept;
// Arm torques (N m) producing grip force f (N) at p: tau = J^T f.
KinStatus joint_torques(const FalconGeometry& g, const Vec3& p, const Vec3& f, std::array<double, 3>& tau) noexcept;
// Grip force (N) that arm torques tau (N m) produce at p: f = M^T tau (inverse of joint_torques).
KinStatus grip_force(const FalconGeometry& g, const Vec3& p, const std::array<double, 3>& tau, Vec3& f) noexcept;

// The driver's view: the same functions on one geometry, with bool results.
class FalconKinematics {
public:
    explicit FalconKinematics(const FalconGeometry& g = {}) : g_(g) {}
    const FalconGeometry& geometry() const noexcept { return g_; }

    bool inverse(const Vec3& p, std::array<double, 3>& theta) const noexcept {
        return inverse_kinematics(g_, p, theta) == KinStatus::ok;
    }
    bool forward(const std::array<double, 3>& theta, const Vec3& guess, Vec3& p) const noexcept {
        return forward_kinematics(g_, theta, guess, p) == KinStatus::ok;
    }
    bool torques(const Vec3& p, const Vec3& f, std::array<double, 3>& tau) const noexcept {
        return joint_torques(g_, p, f, tau) == KinStatus::ok;
    }
    bool force(const Vec3& p, const std::array<double, 3>& tau, Vec3& f) const noexcept {
        return grip_force(g_, p, tau, f) == KinStatus::ok;
    }

    // Encoder counts <-> driven angle t1 (rad) of one arm; counts_of rounds and clamps to int16.
    double theta_of(int arm, std::int32_t counts) const noexcept;
    std::int16_t counts_of(int arm, double theta) const noexcept;
    double counts_exact(int arm, double theta) const noexcept;  // unrounded, unclamped

private:
    FalconGeometry g_;
};

struct FalconPlanarParams {
    Vec2 origin{0.0, 0.0};         // m: world point that the device's (x, y) = (0, 0) maps to
    double z0 = 0.11;              // m: depth of the rendering plane in the device frame
    double z_stiffness = 400.0;    // N/m: restoring spring on the out-of-plane axis
    double z_max_force = 2.0;      // N: that spring's force is clamped to this
    double max_force = 4.0;        // N: in-plane force magnitude clamp at the grip
    // Firmware drive units per N m of arm torque. The published model's scale and sign: -10000
    // (a positive drive unit turns the arm toward smaller t1).
    double motor_counts_per_nm = -10000.0;
    std::int16_t motor_max = 4000; // per-motor saturation, firmware units (well inside int16)
};

// Grip force for the plane: the in-plane force clamped to max_force (direction kept), the
// out-of-plane spring -k (z - z0) clamped to z_max_force; NaN anywhere gives zero.
Vec3 planar_force(const FalconPlanarParams& p, Vec2 in_plane, double z) noexcept;
// Torques -> firmware drive units, each saturated to +-motor_max; NaN gives zero.
std::array<std::int16_t, 3> motor_counts(const FalconPlanarParams& p, const std::array<double, 3>& tau) noexcept;

}  // namespace contactlab::drivers::falcon
