// haply_kinematics.cpp — the 2DIY pantograph (see haply_kinematics.hpp).
#include "drivers/usb/haply_kinematics.hpp"

#include <cmath>

namespace contactlab::drivers::haply {

namespace {

// A pose closer than this to a singular one (the sine of the angle between the links, or between
// the two distal links) is refused: J and J^-1 grow as its inverse, and an encoder count there
// moves the handle by more than the mechanism can render.
constexpr double kMinSine = 1e-6;

bool finite(double a, double b) noexcept { return std::isfinite(a) && std::isfinite(b); }

struct Elbows {
    Vec a, b;    // m: elbows A and B
    Vec da, db;  // m/rad: dA/dt1, dB/dt2
};

Elbows elbows(const PantographGeometry& g, const std::array<double, 2>& t) noexcept {
    const double c1 = std::cos(t[0]), s1 = std::sin(t[0]);
    const double c2 = std::cos(t[1]), s2 = std::sin(t[1]);
    return {{g.l * c1, g.l * s1}, {g.d + g.l * c2, g.l * s2}, {-g.l * s1, g.l * c1}, {-g.l * s2, g.l * c2}};
}

// The handle from the elbows: the midpoint of A B moved along the left normal of A -> B by the
// height of the isosceles triangle A P B (sides L, L, |B - A|).
KinStatus handle(const PantographGeometry& g, const Elbows& e, Vec& p) noexcept {
    const double hx = e.b.x - e.a.x, hy = e.b.y - e.a.y;
    const double h = std::hypot(hx, hy);  // m
    if (!(h > 0.0)) return KinStatus::singular;  // A = B: the handle may be anywhere on a circle
    const double half = 0.5 * h;
    if (half > g.L) return KinStatus::unreachable;
    const double height = std::sqrt((g.L - half) * (g.L + half));  // m
    p = {e.a.x + 0.5 * hx - height * hy / h, e.a.y + 0.5 * hy + height * hx / h};
    return KinStatus::ok;
}

}  // namespace

HaplyHardware hardware(int generation, bool* ok) noexcept {
    HaplyHardware h;
    if (ok != nullptr) *ok = generation == 2 || generation == 3;
    // Motor 1 (t1, the left arm) is wired to port 2, motor 2 to port 1 on both boards.
    if (generation == 2) {
        h.generation = 2;
        h.geometry = {0.07, 0.09, 0.0};
        h.actuator = {ActuatorSetup{1, 2}, ActuatorSetup{0, 1}};
        h.encoder = {EncoderSetup{241.0, 10752.0, 1, 2}, EncoderSetup{-61.0, 10752.0, 0, 1}};
    } else {
        h.generation = 3;
        h.geometry = {0.07, 0.09, 0.038};
        h.actuator = {ActuatorSetup{1, 2}, ActuatorSetup{1, 1}};
        h.encoder = {EncoderSetup{168.0, 4880.0, 1, 2}, EncoderSetup{12.0, 4880.0, 1, 1}};
    }
    return h;
}

const char* to_string(KinStatus s) noexcept {
    switch (s) {
        case KinStatus::ok: return "ok";
        case KinStatus::unreachable: return "unreachable";
        case KinStatus::singular: return "singular";
        case KinStatus::not_finite: return "not finite";
    }
    return "unknown";
}

KinStatus forward_kinematics(const PantographGeometry& g, const std::array<double, 2>& t, Vec& p) noexcept {
    if (!finite(t[0], t[1])) return KinStatus::not_finite;
    Vec out;
    const KinStatus st = handle(g, elbows(g, t), out);
    if (st == KinStatus::ok) p = out;
    return st;
}

KinStatus inverse_kinematics(const PantographGeometry& g, Vec p, std::array<double, 2>& t) noexcept {
    if (!finite(p.x, p.y)) return KinStatus::not_finite;
    // Each arm: the elbow is where the circle of radius l about the motor meets the circle of
    // radius L about P. Motor 1's elbow turns counter-clockwise from the direction to P (outward,
    // to the left), motor 2's clockwise (outward, to the right): the assembly `handle` builds.
    std::array<double, 2> out{};
    const double ox[2] = {0.0, g.d};
    const double sense[2] = {1.0, -1.0};
    for (int i = 0; i < 2; ++i) {
        const double dx = p.x - ox[i], dy = p.y;
        const double r = std::hypot(dx, dy);  // m
        if (!(r > 0.0)) return KinStatus::singular;
        const double c = (g.l * g.l + r * r - g.L * g.L) / (2.0 * g.l * r);
        if (!(c >= -1.0 && c <= 1.0)) return KinStatus::unreachable;
        out[i] = std::atan2(dy, dx) + sense[i] * std::acos(c);
    }
    // The other assembly (P on the right of A -> B) has the same arm lengths: check the one built.
    Vec back;
    if (forward_kinematics(g, out, back) != KinStatus::ok) return KinStatus::unreachable;
    const double tol = 1e-9 * (g.l + g.L);  // m: round-off of the circle intersections
    if (std::hypot(back.x - p.x, back.y - p.y) > tol) return KinStatus::unreachable;
    t = out;
    return KinStatus::ok;
}

KinStatus jacobian(const PantographGeometry& g, const std::array<double, 2>& t, Mat2& J) noexcept {
    if (!finite(t[0], t[1])) return KinStatus::not_finite;
    const Elbows e = elbows(g, t);
    Vec p;
    const KinStatus st = handle(g, e, p);
    if (st != KinStatus::ok) return st;
    // M dP = D dt, rows of M: (P - A)^T, (P - B)^T (each of length L).
    const double m00 = p.x - e.a.x, m01 = p.y - e.a.y;
    const double m10 = p.x - e.b.x, m11 = p.y - e.b.y;
    const double det = m00 * m11 - m01 * m10;  // m^2 = L^2 sin(angle between the distal links)
    const double d0 = m00 * e.da.x + m01 * e.da.y;  // m^2/rad = l L sin(angle between link 1's parts)
    const double d1 = m10 * e.db.x + m11 * e.db.y;
    const double L2 = g.L * g.L;
    if (!(std::fabs(det) > kMinSine * L2) || !(std::fabs(d0) > kMinSine * g.l * g.L) ||
        !(std::fabs(d1) > kMinSine * g.l * g.L))
        return KinStatus::singular;
    // J = M^-1 D.
    J = {{{m11 * d0 / det, -m01 * d1 / det}, {-m10 * d0 / det, m00 * d1 / det}}};
    return KinStatus::ok;
}

KinStatus joint_torques(const PantographGeometry& g, const std::array<double, 2>& t, Vec f,
                        std::array<double, 2>& tau) noexcept {
    if (!finite(f.x, f.y)) return KinStatus::not_finite;
    Mat2 J{};
    const KinStatus st = jacobian(g, t, J);
    if (st != KinStatus::ok) return st;
    tau = {J[0][0] * f.x + J[1][0] * f.y, J[0][1] * f.x + J[1][1] * f.y};
    return KinStatus::ok;
}

Aabb workspace(const PantographGeometry& g) noexcept {
    // 12 cm across, centred between the motors, 4..11 cm from their axis: inside it every arm
    // keeps at least 25 degrees from its singular poses for l = 0.07, L = 0.09 (tests/drivers).
    Aabb box;
    box.lo = {0.5 * g.d - 0.06, 0.04};
    box.hi = {0.5 * g.d + 0.06, 0.11};
    return box;
}

}  // namespace contactlab::drivers::haply
