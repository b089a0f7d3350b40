// haply_kinematics.hpp — the Haply 2DIY's five-bar pantograph: forward and inverse kinematics, the
// Jacobian and the motor torques J^T F, in SI units, with the published constants of both board
// generations (Haply's hAPI, the Pantograph mechanism and its examples' encoder set-up).
//
// Frame (hAPI's): motor 1's axis at the origin, motor 2's axis at (d, 0); x along the line of the
// motor axes, y toward the handle (the workspace is at y > 0), angles counter-clockwise from +x
// toward +y. Each motor turns a proximal link of length l; two distal links of length L join at
// the handle P:
//     A = l (cos t1, sin t1),   B = (d, 0) + l (cos t2, sin t2),   |P - A| = |P - B| = L,
// and P is the intersection of the two circles on the left of A -> B (the assembly the 2DIY is
// built in: elbows outward, the handle away from the motors).
// Differentiating |P - A|^2 = L^2 and |P - B|^2 = L^2 gives M dP = D dt with M's rows (P - A)^T,
// (P - B)^T and D = diag((P - A) . A'(t1), (P - B) . B'(t2)), so the Jacobian is J = dP/dt =
// M^-1 D and the motor torques producing a handle force F are tau = J^T F (N m).
// Singular where the distal links are parallel (det M = 0: the handle at the edge of the reach,
// or A = B) or a proximal link is aligned with its distal link (a zero in D: that arm fully
// stretched or folded). Both are named statuses; nothing here returns a NaN.
#pragma once

#include "drivers/device.hpp"

#include <array>
#include <cstdint>

namespace contactlab::drivers::haply {

inline constexpr double kDegree = 0.017453292519943295;  // rad per degree

struct PantographGeometry {
    double l = 0.07;    // m: proximal links (motor to elbow)
    double L = 0.09;    // m: distal links (elbow to handle)
    double d = 0.038;   // m: distance between the two motor axes
};

// One encoder as the board is told in the parameter message: the angle it reads at its count 0,
// its counts per turn, its sense and the motor port it is wired to.
struct EncoderSetup {
    double offset_deg = 0.0;      // deg: angle at count 0 (the rest pose against the stop)
    double counts_per_rev = 0.0;  // counts per turn of the motor
    std::uint8_t direction = 0;   // 0 clockwise, 1 counter-clockwise (hAPI's CW / CCW)
    std::uint8_t port = 1;        // board motor port 1..4
};
struct ActuatorSetup {
    std::uint8_t direction = 0;   // 0 clockwise, 1 counter-clockwise
    std::uint8_t port = 1;        // board motor port 1..4
};

// A 2DIY generation: its geometry and its motors' and encoders' set-up (hAPI's published values).
struct HaplyHardware {
    int generation = 3;
    PantographGeometry geometry;
    std::array<ActuatorSetup, 2> actuator{};  // motor 1 (t1), motor 2 (t2)
    std::array<EncoderSetup, 2> encoder{};
};
// Generation 2 (the first 2DIY hAPI supports): d = 0, encoders 241 / -61 deg at count 0, 10,752
// counts per turn, motor 2 reversed. Generation 3 (current): d = 0.038 m, 168 / 12 deg, 4,880
// counts per turn. Both: l = 0.07 m, L = 0.09 m; motor 1 on port 2, motor 2 on port 1.
// Throws nothing: an unknown generation gives generation 3 with `ok` false.
HaplyHardware hardware(int generation, bool* ok = nullptr) noexcept;

struct Vec {
    double x = 0.0, y = 0.0;
};
using Mat2 = std::array<std::array<double, 2>, 2>;  // row-major

enum class KinStatus {
    ok,
    unreachable,  // the two distal circles do not meet (|B - A| > 2 L), or no angle reaches P
    singular,     // the Jacobian cannot be inverted / has no finite value here
    not_finite,   // an input is NaN or infinite
};
const char* to_string(KinStatus s) noexcept;

// Handle position P (m) for motor angles t (rad).
KinStatus forward_kinematics(const PantographGeometry& g, const std::array<double, 2>& t, Vec& p) noexcept;
// Motor angles t (rad) that put the handle at p (m), in the assembly forward_kinematics assumes.
KinStatus inverse_kinematics(const PantographGeometry& g, Vec p, std::array<double, 2>& t) noexcept;
// J = dP/dt (m/rad) at motor angles t.
KinStatus jacobian(const PantographGeometry& g, const std::array<double, 2>& t, Mat2& J) noexcept;
// Motor torques (N m) for handle force f (N) at motor angles t: tau = J^T f.
KinStatus joint_torques(const PantographGeometry& g, const std::array<double, 2>& t, Vec f,
                        std::array<double, 2>& tau) noexcept;

// The box (m, device frame) where a generation's handle works: reachable with both arms away
// from their singular poses (checked by the tests at every point of a grid over it).
Aabb workspace(const PantographGeometry& g) noexcept;

}  // namespace contactlab::drivers::haply
