// test_falcon.cpp — Falcon packets, stream reassembly, delta kinematics and the force packer at
// their limits (no USB).
#include "drivers/usb/falcon_kinematics.hpp"
#include "drivers/usb/falcon_protocol.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

using namespace contactlab;
using namespace contactlab::drivers::falcon;

TEST_CASE("falcon packet: extremes of every motor value round-trip through the nibble armour") {
    Command c;
    c.motor = {std::numeric_limits<std::int16_t>::min(), std::numeric_limits<std::int16_t>::max(), -1};
    c.flags = kLedRed | kHomingMode;
    std::uint8_t p[kPacketSize];
    pack(c, p);
    CHECK(p[0] == '<');
    CHECK(p[15] == '>');
    for (int i = 1; i <= 14; ++i) {
        CHECK(p[i] >= 'A');
        CHECK(p[i] <= 'P');  // framing characters can never appear inside
    }
    CHECK(p[13] == 'A' + (kLedRed | kHomingMode));
    // The Falcon answers in the same layout: read our own packet back as a state.
    State s;
    REQUIRE(unpack(p, sizeof p, s));
    CHECK(s.encoder[0] == -32768);
    CHECK(s.encoder[1] == 32767);
    CHECK(s.encoder[2] == -1);
    CHECK(s.buttons == (kLedRed | kHomingMode));
    CHECK(s.homed == 0);
}

TEST_CASE("falcon packet: homing status in the high bits of byte 13") {
    std::uint8_t p[kPacketSize];
    pack(Command{}, p);
    p[13] = static_cast<std::uint8_t>('A' + (0x7 << 4) + 0x2);  // all three arms homed, button 2
    State s;
    REQUIRE(unpack(p, sizeof p, s));
    CHECK(s.homed == 7);
    CHECK(s.buttons == 2);
}

TEST_CASE("falcon packet: wrong brackets, a non-nibble byte or a short packet is refused") {
    std::uint8_t good[kPacketSize];
    pack(Command{}, good);
    State s;
    CHECK_FALSE(unpack(good, kPacketSize - 1, s));
    std::uint8_t b[kPacketSize];
    std::memcpy(b, good, sizeof b);
    b[0] = '[';
    CHECK_FALSE(unpack(b, sizeof b, s));
    std::memcpy(b, good, sizeof b);
    b[15] = ']';
    CHECK_FALSE(unpack(b, sizeof b, s));
    std::memcpy(b, good, sizeof b);
    b[7] = 'Q';  // 0x51: not a nibble
    CHECK_FALSE(unpack(b, sizeof b, s));
}

TEST_CASE("falcon stream: modem-status bytes dropped, packets split across USB packets joined, junk counted") {
    Command c;
    c.motor = {100, -200, 300};
    std::uint8_t p[kPacketSize];
    pack(c, p);
    // USB packet 1 (64 bytes): 2 modem-status bytes, 36 junk bytes, one packet, the first 10
    // bytes of the next. USB packet 2 (short, ends the transfer): 2 status bytes, the other 6
    // bytes, 5 bytes of a packet cut short by a new '<', then one whole packet.
    std::vector<std::uint8_t> t{0x31, 0x60};
    t.insert(t.end(), kFtdiPacket - 2 - 16 - 10, 'j');
    t.insert(t.end(), p, p + 16);
    t.insert(t.end(), p, p + 10);
    REQUIRE(t.size() == kFtdiPacket);
    t.insert(t.end(), {0x31, 0x60});
    t.insert(t.end(), p + 10, p + 16);
    t.insert(t.end(), p, p + 5);
    t.insert(t.end(), p, p + 16);
    StreamParser parser;
    std::vector<State> got;
    CHECK(parser.feed(t.data(), t.size(), [&](const State& s) { got.push_back(s); }) == 3);
    REQUIRE(got.size() == 3);
    for (const State& s : got) {
        CHECK(s.encoder[0] == 100);
        CHECK(s.encoder[1] == -200);
        CHECK(s.encoder[2] == 300);
    }
    CHECK(parser.malformed() == 1);             // the packet cut short
    CHECK(parser.discarded_bytes() == 36 + 5);  // the junk and the cut packet's 5 bytes
}

namespace {

// The published encoder scale: 4 x 320 slots x 110 mm drum / 14.25 mm shaft counts per turn.
constexpr double kCountsPerRev = 4.0 * 320.0 * 110.0 / 14.25;  // 9880.70...

// A grid over the Falcon's workspace (m): +-4 cm across, 9..15 cm out along the axis.
std::vector<Vec3> workspace_grid() {
    std::vector<Vec3> g;
    for (double x : {-0.04, 0.0, 0.04})
        for (double y : {-0.04, 0.0, 0.04})
            for (double z : {0.09, 0.11, 0.13, 0.15}) g.push_back({x, y, z});
    return g;
}

}  // namespace

TEST_CASE("falcon encoders: 35 degrees at count 0 and 360/9880.7 degrees per count, for every arm") {
    FalconKinematics k;
    CHECK(k.geometry().counts_per_rev() == doctest::Approx(kCountsPerRev).epsilon(1e-12));
    CHECK(k.geometry().counts_per_rev() == doctest::Approx(9880.7).epsilon(1e-5));
    for (int arm = 0; arm < 3; ++arm) {
        CHECK(k.theta_of(arm, 0) / kDegree == doctest::Approx(35.0).epsilon(1e-12));
        for (int counts : {-4000, -1, 1, 1234, 9880}) {
            const double deg = (k.theta_of(arm, counts) - k.theta_of(arm, 0)) / kDegree;
            CHECK(deg == doctest::Approx(counts * 360.0 / kCountsPerRev).epsilon(1e-12));
            CHECK(k.counts_of(arm, k.theta_of(arm, counts)) == counts);
        }
    }
    // A full turn of the arm is 9880.7 counts: 9881 after rounding.
    CHECK(k.counts_of(1, k.theta_of(1, 0) + kTwoPi) == 9881);
    CHECK(k.counts_of(0, 100.0) == 32767);
    CHECK(k.counts_of(0, -100.0) == -32768);
}

TEST_CASE("falcon kinematics: equal arm angles put the grip on the device axis, and the legs are three-fold symmetric") {
    FalconKinematics k;
    for (double deg : {0.0, 20.0, 35.0, 50.0}) {
        const std::array<double, 3> th{deg * kDegree, deg * kDegree, deg * kDegree};
        Vec3 p;
        REQUIRE(k.forward(th, Vec3{0.02, -0.01, 0.11}, p));
        CHECK(std::fabs(p.x) < 1e-9);
        CHECK(std::fabs(p.y) < 1e-9);
        CHECK(p.z > 0.07);
        CHECK(p.z < 0.18);
    }
    // Turning the grip by -120 degrees about z hands each leg its predecessor's angle.
    const double c = std::cos(-kTwoPi / 3.0), s = std::sin(-kTwoPi / 3.0);
    for (const Vec3& p : workspace_grid()) {
        std::array<double, 3> t{}, tr{};
        REQUIRE(k.inverse(p, t));
        REQUIRE(k.inverse({c * p.x - s * p.y, s * p.x + c * p.y, p.z}, tr));
        CHECK(tr[1] == doctest::Approx(t[0]).epsilon(1e-12));
        CHECK(tr[2] == doctest::Approx(t[1]).epsilon(1e-12));
        CHECK(tr[0] == doctest::Approx(t[2]).epsilon(1e-12));
    }
    // Grip further out along +z: every thigh angle grows.
    std::array<double, 3> near{}, far{};
    REQUIRE(k.inverse({0.0, 0.0, 0.10}, near));
    REQUIRE(k.inverse({0.0, 0.0, 0.14}, far));
    for (int i = 0; i < 3; ++i) CHECK(far[i] > near[i]);
}

TEST_CASE("falcon kinematics: forward of inverse returns the grip position to 1e-9 m across the workspace") {
    FalconKinematics k;
    for (const Vec3& q : workspace_grid()) {
        std::array<double, 3> th{};
        REQUIRE(k.inverse(q, th));
        Vec3 p;
        REQUIRE(k.forward(th, Vec3{0.0, 0.0, 0.11}, p));
        CHECK(std::fabs(p.x - q.x) < 1e-9);
        CHECK(std::fabs(p.y - q.y) < 1e-9);
        CHECK(std::fabs(p.z - q.z) < 1e-9);
    }
    std::array<double, 3> th{};
    CHECK(inverse_kinematics(k.geometry(), {0.0, 0.0, 0.5}, th) == KinStatus::unreachable);  // beyond reach
}

TEST_CASE("falcon kinematics: angles no pose can take give a named status and leave the position alone") {
    const FalconGeometry g;
    Vec3 p{1.0, 2.0, 3.0};
    CHECK(forward_kinematics(g, {170.0 * kDegree, -170.0 * kDegree, 170.0 * kDegree}, Vec3{0.0, 0.0, 0.11}, p) !=
          KinStatus::ok);
    CHECK(forward_kinematics(g, {std::nan(""), 0.0, 0.0}, Vec3{0.0, 0.0, 0.11}, p) == KinStatus::unreachable);
    CHECK(p.x == 1.0);
    CHECK(p.y == 2.0);
    CHECK(p.z == 3.0);
    CHECK(std::string(to_string(KinStatus::no_convergence)) == "no_convergence");
}

TEST_CASE("falcon kinematics: behind the base only the mirror assembly reaches, and it is refused") {
    // The legs' equations solve for a grip 11 cm behind the plane of the hip axes with the thighs
    // folded back to -189 deg (the mirror of the device through its base); on and behind that
    // plane nothing is reachable, and in front no thigh folds back past -90 deg.
    const FalconGeometry g;
    std::array<double, 3> th{1.0, 2.0, 3.0};
    for (const Vec3& p : {Vec3{0.0, 0.0, -0.11}, Vec3{0.1, 0.0, 0.0}, Vec3{0.06, 0.0, -0.11}, Vec3{0.0, 0.0, -0.0}}) {
        CAPTURE(p.z);
        CHECK(inverse_kinematics(g, p, th) == KinStatus::unreachable);
    }
    CHECK(th == std::array<double, 3>{1.0, 2.0, 3.0});  // left alone
    for (const Vec3& p : workspace_grid()) {
        REQUIRE(inverse_kinematics(g, p, th) == KinStatus::ok);
        for (double t : th) CHECK(t > kMinThighAngle);
    }
}

TEST_CASE("falcon kinematics: the analytic Jacobians match finite differences of inverse and forward") {
    const FalconGeometry g;
    for (const Vec3& p : workspace_grid()) {
        Mat3 M{}, J{};
        REQUIRE(angle_jacobian(g, p, M) == KinStatus::ok);
        REQUIRE(jacobian(g, p, J) == KinStatus::ok);
        std::array<double, 3> th{};
        REQUIRE(inverse_kinematics(g, p, th) == KinStatus::ok);
        constexpr double h = 1e-6;  // m or rad
        for (int j = 0; j < 3; ++j) {
            Vec3 a = p, b = p;
            (j == 0 ? a.x : j == 1 ? a.y : a.z) += h;
            (j == 0 ? b.x : j == 1 ? b.y : b.z) -= h;
            std::array<double, 3> ta{}, tb{};
            REQUIRE(inverse_kinematics(g, a, ta) == KinStatus::ok);
            REQUIRE(inverse_kinematics(g, b, tb) == KinStatus::ok);
            for (int i = 0; i < 3; ++i) CHECK(M[i][j] == doctest::Approx((ta[i] - tb[i]) / (2.0 * h)).epsilon(1e-6).scale(1.0));
            // Column j of J: the grip's motion when arm j alone turns.
            std::array<double, 3> tha = th, thb = th;
            tha[j] += h;
            thb[j] -= h;
            Vec3 pa, pb;
            REQUIRE(forward_kinematics(g, tha, p, pa) == KinStatus::ok);
            REQUIRE(forward_kinematics(g, thb, p, pb) == KinStatus::ok);
            CHECK(J[0][j] == doctest::Approx((pa.x - pb.x) / (2.0 * h)).epsilon(1e-6).scale(0.01));
            CHECK(J[1][j] == doctest::Approx((pa.y - pb.y) / (2.0 * h)).epsilon(1e-6).scale(0.01));
            CHECK(J[2][j] == doctest::Approx((pa.z - pb.z) / (2.0 * h)).epsilon(1e-6).scale(0.01));
        }
    }
}

TEST_CASE("falcon kinematics: torques do the same virtual work as the force (tau . dtheta = f . dp)") {
    FalconKinematics k;
    const Vec3 f{1.0, -2.0, 0.5};
    for (const Vec3& p : workspace_grid()) {
        std::array<double, 3> tau{};
        REQUIRE(k.torques(p, f, tau));
        const Vec3 dp{1e-7, 2e-7, -1e-7};
        std::array<double, 3> t0{}, t1{};
        REQUIRE(k.inverse({p.x - dp.x, p.y - dp.y, p.z - dp.z}, t0));
        REQUIRE(k.inverse({p.x + dp.x, p.y + dp.y, p.z + dp.z}, t1));
        const double w_tau = tau[0] * (t1[0] - t0[0]) + tau[1] * (t1[1] - t0[1]) + tau[2] * (t1[2] - t0[2]);
        const double w_f = 2.0 * (f.x * dp.x + f.y * dp.y + f.z * dp.z);
        CHECK(w_tau == doctest::Approx(w_f).epsilon(1e-6));
        Vec3 back;
        REQUIRE(k.force(p, tau, back));
        CHECK(back.x == doctest::Approx(1.0).epsilon(1e-9));
        CHECK(back.y == doctest::Approx(-2.0).epsilon(1e-9));
        CHECK(back.z == doctest::Approx(0.5).epsilon(1e-9));
    }
}

TEST_CASE("falcon planar force: in-plane magnitude clamped first, the out-of-plane spring restores and is clamped") {
    FalconPlanarParams pp;
    Vec3 f = planar_force(pp, Vec2{30.0, 40.0}, pp.z0);  // 50 N asked, 4 N allowed
    CHECK(std::hypot(f.x, f.y) == doctest::Approx(4.0));
    CHECK(f.x / f.y == doctest::Approx(0.75));  // direction kept
    CHECK(f.z == 0.0);
    f = planar_force(pp, Vec2{0.0}, pp.z0 + 0.001);  // 1 mm toward the user
    CHECK(f.z == doctest::Approx(-0.4));              // pushed back at 400 N/m
    f = planar_force(pp, Vec2{0.0}, pp.z0 - 0.05);
    CHECK(f.z == doctest::Approx(2.0));                // clamped
    f = planar_force(pp, Vec2{std::nan(""), 0.0}, pp.z0);
    CHECK(f.x == 0.0);
    CHECK(f.y == 0.0);
    CHECK(f.z == 0.0);
}

TEST_CASE("falcon motor packer: then each motor saturated to its limit, and NaN switches all motors off") {
    FalconPlanarParams pp;
    // The published scale: -10000 drive units per N m.
    auto m = motor_counts(pp, {0.1, -0.2, 0.0});
    CHECK(m[0] == -1000);
    CHECK(m[1] == 2000);
    CHECK(m[2] == 0);
    m = motor_counts(pp, {5.0, -5.0, 0.39999});  // -50000 and 50000 counts asked
    CHECK(m[0] == -4000);
    CHECK(m[1] == 4000);
    CHECK(m[2] == -4000);
    m = motor_counts(pp, {0.1, std::numeric_limits<double>::infinity(), 0.1});
    CHECK(m[0] == 0);
    CHECK(m[1] == 0);
    CHECK(m[2] == 0);
}
