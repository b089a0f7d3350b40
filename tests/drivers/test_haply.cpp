// test_haply.cpp — the Haply 2DIY's pantograph against hAPI's published equations, its Jacobian
// against finite differences, and the hAPI frames byte by byte (no serial port).
//
// The reference below is the form Haply publishes for the Pantograph mechanism (the elbows A, B;
// the foot of the handle on A B at L cos(beta) from A, with cos(beta) = |B - A| / (2 L); then out
// along the left normal by L sin(beta); and the torques through the distal links' angles phi1,
// phi2 taken with acos), written from the equations, not from the driver's code.
#include "drivers/usb/haply_kinematics.hpp"
#include "drivers/usb/haply_protocol.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace contactlab::drivers::haply;

namespace {

struct Published {
    Vec p;
    std::array<double, 2> tau{};
    double elbow_y[2]{};
    double min_sin = 0.0;  // the smaller sine of the distal links' angles phi1, phi2
};

// hAPI's Pantograph: forward kinematics and J^T f, for equal proximal (l) and distal (L) links.
Published published(const PantographGeometry& g, double t1, double t2, double fx, double fy) {
    const double l = g.l, L = g.L, d = g.d;
    const double c1 = std::cos(t1), s1 = std::sin(t1), c2 = std::cos(t2), s2 = std::sin(t2);
    const double xA = l * c1, yA = l * s1, xB = d + l * c2, yB = l * s2;
    const double hx = xB - xA, hy = yB - yA;
    const double hh = hx * hx + hy * hy, hm = std::sqrt(hh);
    const double cB = -(L * L - L * L - hh) / (2.0 * L * hm);
    const double h1x = L * cB * hx / hm, h1y = L * cB * hy / hm;
    const double h1m = std::sqrt(h1x * h1x + h1y * h1y);
    const double sB = std::sqrt(1.0 - cB * cB);
    const double lx = -L * sB * h1y / h1m, ly = L * sB * h1x / h1m;
    Published out;
    out.p = {xA + h1x + lx, yA + h1y + ly};
    out.elbow_y[0] = yA;
    out.elbow_y[1] = yB;
    const double phi1 = std::acos((out.p.x - l * c1) / L), phi2 = std::acos((out.p.x - d - l * c2) / L);
    const double c11 = std::cos(phi1), s11 = std::sin(phi1), c22 = std::cos(phi2), s22 = std::sin(phi2);
    out.min_sin = std::min(std::fabs(s11), std::fabs(s22));
    const double dn = L * (c11 * s22 - c22 * s11);
    const double eta = (-L * c11 * s22 + L * c22 * s11 - c1 * l * s22 + c22 * l * s1) / dn;
    const double nu = l * (c2 * s22 - c22 * s2) / dn;
    const double JT11 = -L * eta * s11 - L * s11 - l * s1, JT12 = L * c11 * eta + L * c11 + c1 * l;
    const double JT21 = -L * s11 * nu, JT22 = L * c11 * nu;
    out.tau = {JT11 * fx + JT12 * fy, JT21 * fx + JT22 * fy};
    return out;
}

// Every 2 mm over the declared workspace (plus its edges), motor angles from the inverse.
template <class F>
int over_workspace(const PantographGeometry& g, F f) {
    const contactlab::Aabb box = workspace(g);
    int n = 0;
    for (double x = box.lo.x; x <= box.hi.x + 1e-12; x += 0.002)
        for (double y = box.lo.y; y <= box.hi.y + 1e-12; y += 0.002) {
            std::array<double, 2> t{};
            REQUIRE(inverse_kinematics(g, Vec{x, y}, t) == KinStatus::ok);
            f(Vec{x, y}, t);
            ++n;
        }
    return n;
}

}  // namespace

TEST_CASE("haply hardware: the published link lengths and encoder set-up of both generations") {
    bool ok = false;
    const HaplyHardware h3 = hardware(3, &ok);
    CHECK(ok);
    CHECK(h3.geometry.l == 0.07);
    CHECK(h3.geometry.L == 0.09);
    CHECK(h3.geometry.d == 0.038);
    CHECK(h3.encoder[0].offset_deg == 168.0);
    CHECK(h3.encoder[1].offset_deg == 12.0);
    CHECK(h3.encoder[0].counts_per_rev == 4880.0);
    CHECK(h3.encoder[1].counts_per_rev == 4880.0);
    const HaplyHardware h2 = hardware(2, &ok);
    CHECK(ok);
    CHECK(h2.geometry.d == 0.0);
    CHECK(h2.geometry.l == 0.07);
    CHECK(h2.geometry.L == 0.09);
    hardware(1, &ok);
    CHECK_FALSE(ok);
}

TEST_CASE("haply kinematics: forward kinematics match hAPI's published equations to 1e-9 m over the workspace") {
    for (int gen : {2, 3}) {
        const PantographGeometry g = hardware(gen).geometry;
        double worst = 0.0;  // m
        const int n = over_workspace(g, [&](Vec p, const std::array<double, 2>& t) {
            Vec q;
            REQUIRE(forward_kinematics(g, t, q) == KinStatus::ok);
            const Published ref = published(g, t[0], t[1], 0.0, 0.0);
            worst = std::max({worst, std::hypot(q.x - ref.p.x, q.y - ref.p.y), std::hypot(q.x - p.x, q.y - p.y)});
        });
        INFO("generation " << gen << ": " << n << " points, worst " << worst << " m");
        CHECK(n == 61 * 36);
        CHECK(worst < 1e-9);
    }
}

TEST_CASE("haply kinematics: J^T maps a handle force to hAPI's published torques, and J matches finite differences") {
    for (int gen : {2, 3}) {
        const PantographGeometry g = hardware(gen).geometry;
        double worst_tau = 0.0, worst_j = 0.0;
        int points = 0, compared = 0;
        over_workspace(g, [&](Vec, const std::array<double, 2>& t) {
            // The published torques take the distal links' angles with acos, which holds only
            // where the handle is beyond both elbows (y_P > y_A, y_B); nearer the motors acos
            // returns the mirrored angle. There J is checked against finite differences alone.
            const Published ref0 = published(g, t[0], t[1], 0.0, 0.0);
            ++points;
            if (ref0.p.y > ref0.elbow_y[0] && ref0.p.y > ref0.elbow_y[1]) {
                ++compared;
                for (const Vec f : {Vec{1.0, 0.0}, Vec{0.0, 1.0}, Vec{-0.7, 1.3}}) {  // N
                    std::array<double, 2> tau{};
                    REQUIRE(joint_torques(g, t, f, tau) == KinStatus::ok);
                    const Published ref = published(g, t[0], t[1], f.x, f.y);
                    // acos's argument carries a rounding of ~eps, which becomes eps / sin(phi) in
                    // the angle and (l + L) |f| times that in a torque: the published form loses
                    // digits where the handle is nearly level with an elbow (phi near 0 or pi).
                    const double tol = 1e-13 + (g.l + g.L) * std::hypot(f.x, f.y) * 8.0 *
                                                   std::numeric_limits<double>::epsilon() / ref.min_sin;
                    const double err = std::max(std::fabs(tau[0] - ref.tau[0]), std::fabs(tau[1] - ref.tau[1]));
                    CHECK(err <= tol);
                    worst_tau = std::max(worst_tau, err * 1e-13 / tol);
                }
            }
            // Central differences, h = 1e-6 rad: truncation h^2/6 |P'''| (~1e-12 m/rad here)
            // and round-off eps |P| / h (~1e-11 m/rad), far below the 1e-8 m/rad asserted.
            Mat2 J{};
            REQUIRE(jacobian(g, t, J) == KinStatus::ok);
            const double h = 1e-6;
            for (int c = 0; c < 2; ++c) {
                std::array<double, 2> a = t, b = t;
                a[c] += h;
                b[c] -= h;
                Vec pa, pb;
                REQUIRE(forward_kinematics(g, a, pa) == KinStatus::ok);
                REQUIRE(forward_kinematics(g, b, pb) == KinStatus::ok);
                worst_j = std::max({worst_j, std::fabs((pa.x - pb.x) / (2 * h) - J[0][c]),
                                    std::fabs((pa.y - pb.y) / (2 * h) - J[1][c])});
            }
        });
        INFO("generation " << gen << ": torques within " << worst_tau << " N m (scaled) at " << compared << " of " << points
                            << " points, J within " << worst_j << " m/rad at all");
        MESSAGE("generation " << gen << ": published torques compared at " << compared << " of " << points << " points");
        CHECK(compared * 2 > points);  // most of the workspace is beyond both elbows
        // worst_tau is the worst error scaled to a 1e-13 N m tolerance (checked point by point).
        CHECK(worst_tau <= 1e-13);
        CHECK(worst_j < 1e-8);
    }
}

TEST_CASE("haply kinematics: the workspace keeps every arm 25 degrees from its singular poses") {
    const PantographGeometry g = hardware(3).geometry;
    double worst = 1.0;
    over_workspace(g, [&](Vec p, const std::array<double, 2>& t) {
        const Vec a{g.l * std::cos(t[0]), g.l * std::sin(t[0])}, b{g.d + g.l * std::cos(t[1]), g.l * std::sin(t[1])};
        const Vec ua{(p.x - a.x) / g.L, (p.y - a.y) / g.L}, ub{(p.x - b.x) / g.L, (p.y - b.y) / g.L};
        const double distal = std::fabs(ua.x * ub.y - ua.y * ub.x);  // sin of the angle at the handle
        const double arm1 = std::fabs(-ua.x * std::sin(t[0]) + ua.y * std::cos(t[0]));  // sin at elbow A
        const double arm2 = std::fabs(-ub.x * std::sin(t[1]) + ub.y * std::cos(t[1]));
        worst = std::min({worst, distal, arm1, arm2});
    });
    CHECK(worst > std::sin(25.0 * kDegree));
}

TEST_CASE("haply kinematics: out of reach, singular and non-finite inputs are named, never a NaN") {
    const PantographGeometry g = hardware(3).geometry;
    std::array<double, 2> t{1.0, 2.0};
    CHECK(inverse_kinematics(g, Vec{0.0, 0.3}, t) == KinStatus::unreachable);  // beyond l + L
    CHECK(t[0] == 1.0);
    CHECK(inverse_kinematics(g, Vec{std::nan(""), 0.1}, t) == KinStatus::not_finite);
    Vec p{7.0, 7.0};
    // Elbows 0.038 + 2 x 0.07 = 0.178 m apart along x: just within 2 L = 0.18 m.
    CHECK(forward_kinematics(g, {180.0 * kDegree, 0.0}, p) == KinStatus::ok);
    // Generation 2 (d = 0) with both arms at 180 and 0 degrees: 0.14 m apart, fine; folded onto
    // each other (A = B) the handle is anywhere on a circle.
    const PantographGeometry g2 = hardware(2).geometry;
    CHECK(forward_kinematics(g2, {90.0 * kDegree, 90.0 * kDegree}, p) == KinStatus::singular);
    CHECK(forward_kinematics(g, {0.0, std::numeric_limits<double>::infinity()}, p) == KinStatus::not_finite);
    Mat2 J{};
    // Arm 1 stretched straight (t1 = 80 deg, the distal link along it): the handle is 0.16 m out,
    // arm 2 reaches it (motor 2's elbow outward), and J has no inverse there.
    const double t1 = 80.0 * kDegree;
    const Vec hp{(g.l + g.L) * std::cos(t1), (g.l + g.L) * std::sin(t1)};
    const double r2 = std::hypot(hp.x - g.d, hp.y);
    const double t2 = std::atan2(hp.y, hp.x - g.d) - std::acos((g.l * g.l + r2 * r2 - g.L * g.L) / (2 * g.l * r2));
    Vec q;
    REQUIRE(forward_kinematics(g, {t1, t2}, q) == KinStatus::ok);
    CHECK(std::hypot(q.x - hp.x, q.y - hp.y) < 1e-9);
    CHECK(jacobian(g, {t1, t2}, J) == KinStatus::singular);
    CHECK(jacobian(g, {std::nan(""), 0.0}, J) == KinStatus::not_finite);
    const std::array<double, 2> s{t1 - 0.3, t2};
    std::array<double, 2> tau{3.0, 4.0};
    CHECK(joint_torques(g, s, Vec{std::nan(""), 0.0}, tau) == KinStatus::not_finite);
    CHECK(tau[0] == 3.0);
}

TEST_CASE("hAPI frames: reset, the parameter message of each generation, exchange and reply byte by byte") {
    std::uint8_t reset[kResetSize];
    pack_reset(reset);
    CHECK(reset[0] == 0);
    CHECK(reset[1] == 0);

    std::uint8_t p[kParametersSize];
    pack_parameters(hardware(3), 5, p);
    const std::uint8_t head3[10] = {1, 5, 0x03, 1, 1, 0x03, 1, 1, 0, 0};
    CHECK(std::memcmp(p, head3, 10) == 0);
    // Port order: port 1 is motor 2 (12 deg), port 2 motor 1 (168 deg); 4880 counts per turn.
    CHECK(get_float(p + 10) == 12.0f);
    CHECK(get_float(p + 14) == 4880.0f);
    CHECK(get_float(p + 18) == 168.0f);
    CHECK(get_float(p + 22) == 4880.0f);
    pack_parameters(hardware(2), 3, p);
    const std::uint8_t head2[10] = {1, 3, 0x03, 0, 1, 0x03, 0, 1, 0, 0};
    CHECK(std::memcmp(p, head2, 10) == 0);
    CHECK(get_float(p + 10) == -61.0f);
    CHECK(get_float(p + 14) == 10752.0f);
    CHECK(get_float(p + 18) == 241.0f);
    CHECK(get_float(p + 22) == 10752.0f);

    std::uint8_t ex[kExchangeSize];
    pack_exchange(hardware(3), 5, {0.125, -0.5}, ex);  // N m, motor 1 and 2
    CHECK(ex[0] == 2);
    CHECK(ex[1] == 5);
    CHECK(get_float(ex + 2) == -0.5f);   // port 1: motor 2
    CHECK(get_float(ex + 6) == 0.125f);  // port 2: motor 1
    // Little-endian on the wire: 0.125f is 0x3e000000.
    CHECK(ex[6] == 0x00);
    CHECK(ex[9] == 0x3e);
    pack_exchange(hardware(3), 5, {std::nan(""), std::numeric_limits<double>::infinity()}, ex);
    CHECK(get_float(ex + 2) == 0.0f);
    CHECK(get_float(ex + 6) == 0.0f);
    std::uint8_t id = 0;
    std::array<float, 2> tau{};
    pack_exchange(hardware(3), 5, {0.125, -0.5}, ex);
    REQUIRE(unpack_exchange(hardware(3), ex, sizeof ex, id, tau));
    CHECK(id == 5);
    CHECK(tau[0] == 0.125f);
    CHECK(tau[1] == -0.5f);
    CHECK_FALSE(unpack_exchange(hardware(3), ex, sizeof ex - 1, id, tau));

    std::uint8_t r[kReplySize];
    pack_reply(hardware(3), 5, {150.0f, 30.0f}, r);
    CHECK(r[0] == 5);
    CHECK(get_float(r + 1) == 30.0f);  // port 1: motor 2's encoder
    std::array<double, 2> a{};
    REQUIRE(unpack_reply(hardware(3), 5, r, sizeof r, a) == ReplyError::none);
    CHECK(a[0] == doctest::Approx(150.0 * kDegree).epsilon(1e-15));
    CHECK(a[1] == doctest::Approx(30.0 * kDegree).epsilon(1e-15));
}

TEST_CASE("hAPI replies: short, from another device id or carrying a NaN are refused and leave the angles") {
    std::uint8_t r[kReplySize];
    pack_reply(hardware(3), 5, {150.0f, 30.0f}, r);
    std::array<double, 2> a{7.0, 8.0};
    CHECK(unpack_reply(hardware(3), 5, r, kReplySize - 1, a) == ReplyError::short_frame);
    CHECK(unpack_reply(hardware(3), 5, nullptr, 0, a) == ReplyError::short_frame);
    CHECK(unpack_reply(hardware(3), 6, r, kReplySize, a) == ReplyError::wrong_device);
    pack_reply(hardware(3), 5, {std::numeric_limits<float>::quiet_NaN(), 30.0f}, r);
    CHECK(unpack_reply(hardware(3), 5, r, kReplySize, a) == ReplyError::not_finite);
    pack_reply(hardware(3), 5, {150.0f, std::numeric_limits<float>::infinity()}, r);
    CHECK(unpack_reply(hardware(3), 5, r, kReplySize, a) == ReplyError::not_finite);
    CHECK(a[0] == 7.0);
    CHECK(a[1] == 8.0);
}
