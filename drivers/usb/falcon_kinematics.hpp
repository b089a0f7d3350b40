// falcon_kinematics.hpp — the Falcon as a rotary delta arm, used in a vertical plane.
//
// Model: three upper arms (length L) driven about axes tangent to a circle of radius `base`,
// each connected by a parallelogram of length `lower` to the grip; the grip's attachment points
// lie on a circle of radius `effector`. Device frame: x right, y up, z out of the device toward
// the user; arm i's hip sits at azimuth `azimuth[i]` in the x-y plane; theta_i = 0 is an upper
// arm in the base plane pointing outward, positive toward +z. Inverse kinematics is closed form;
// forward kinematics is Newton's method on it (warm-started from the last pose, a few iterations,
// no allocation). The default geometry approximates a Falcon; calibrate it against yours.
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

struct FalconGeometry {
    double upper = 0.060;          // m, upper arm L
    double lower = 0.1025;         // m, parallelogram length
    double base = 0.0362;          // m, hip circle radius
    double effector = 0.0;         // m, grip attachment circle radius (folded into `base` by default)
    std::array<double, 3> azimuth{1.8326, -0.2618, 3.9270};  // rad: 105, -15, 225 degrees
    double counts_per_rev = 4.0 * 320.0 * 8.75;  // encoder counts per arm revolution (320 lines x4, capstan ~8.75)
    std::array<double, 3> theta_offset{-0.6109, -0.6109, -0.6109};  // rad at count 0 (about -35 degrees)
};

struct FalconPlanarParams {
    Vec2 origin{0.0, 0.0};         // m: world point that the device's (x, y) = (0, 0) maps to
    double z0 = 0.11;              // m: depth of the rendering plane in the device frame
    double z_stiffness = 400.0;    // N/m: restoring spring on the out-of-plane axis
    double z_max_force = 2.0;      // N: that spring's force is clamped to this
    double max_force = 4.0;        // N: in-plane force magnitude clamp at the grip
    double motor_counts_per_nm = 10000.0;  // firmware drive units per N m of arm torque (approximate)
    std::int16_t motor_max = 4000; // per-motor saturation, firmware units (well inside int16)
};

class FalconKinematics {
public:
    explicit FalconKinematics(const FalconGeometry& g = {}) : g_(g) {}
    const FalconGeometry& geometry() const noexcept { return g_; }

    // Arm angles (rad) that put the grip at p (m). False when p is out of reach.
    bool inverse(const Vec3& p, std::array<double, 3>& theta) const noexcept;
    // Grip position for arm angles theta, by Newton iteration from `guess`. False if it did not
    // converge (theta out of the workspace); `p` then keeps the guess.
    bool forward(const std::array<double, 3>& theta, const Vec3& guess, Vec3& p) const noexcept;
    // Arm torques (N m) producing grip force f (N) at p: tau = J^T f with J = dp/dtheta.
    bool torques(const Vec3& p, const Vec3& f, std::array<double, 3>& tau) const noexcept;
    // Grip force (N) that arm torques tau (N m) produce at p (inverse of torques()).
    bool force(const Vec3& p, const std::array<double, 3>& tau, Vec3& f) const noexcept;

    double theta_of(int arm, std::int16_t counts) const noexcept;
    std::int16_t counts_of(int arm, double theta) const noexcept;

private:
    bool dtheta_dp(const Vec3& p, double M[3][3]) const noexcept;
    FalconGeometry g_;
};

// Grip force for the plane: the in-plane force clamped to max_force (direction kept), the
// out-of-plane spring -k (z - z0) clamped to z_max_force; NaN anywhere gives zero.
Vec3 planar_force(const FalconPlanarParams& p, Vec2 in_plane, double z) noexcept;
// Torques -> firmware drive units, each saturated to +-motor_max; NaN gives zero.
std::array<std::int16_t, 3> motor_counts(const FalconPlanarParams& p, const std::array<double, 3>& tau) noexcept;

}  // namespace contactlab::drivers::falcon
