// test_falcon.cpp — Falcon packets, stream reassembly, delta kinematics and the force packer at
// their limits (no USB).
#include "drivers/usb/falcon_kinematics.hpp"
#include "drivers/usb/falcon_protocol.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
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

TEST_CASE("falcon kinematics: inverse then forward returns the grip position across the workspace (+-4 cm cube)") {
    FalconKinematics k;
    for (double x : {-0.04, 0.0, 0.04})
        for (double y : {-0.04, 0.0, 0.04})
            for (double z : {0.09, 0.11, 0.13}) {
                std::array<double, 3> th{};
                REQUIRE(k.inverse({x, y, z}, th));
                Vec3 p;
                REQUIRE(k.forward(th, Vec3{0.0, 0.0, 0.11}, p));
                CHECK(std::fabs(p.x - x) < 1e-9);
                CHECK(std::fabs(p.y - y) < 1e-9);
                CHECK(std::fabs(p.z - z) < 1e-9);
            }
    std::array<double, 3> th{};
    CHECK_FALSE(k.inverse({0.0, 0.0, 0.5}, th));  // beyond reach
}

TEST_CASE("falcon kinematics: torques do the same virtual work as the force (tau . dtheta = f . dp)") {
    FalconKinematics k;
    const Vec3 p{0.01, -0.02, 0.115};
    const Vec3 f{1.0, -2.0, 0.5};
    std::array<double, 3> tau{};
    REQUIRE(k.torques(p, f, tau));
    const Vec3 dp{1e-6, 2e-6, -1e-6};
    std::array<double, 3> t0{}, t1{};
    REQUIRE(k.inverse(p, t0));
    REQUIRE(k.inverse({p.x + dp.x, p.y + dp.y, p.z + dp.z}, t1));
    const double w_tau = tau[0] * (t1[0] - t0[0]) + tau[1] * (t1[1] - t0[1]) + tau[2] * (t1[2] - t0[2]);
    const double w_f = f.x * dp.x + f.y * dp.y + f.z * dp.z;
    CHECK(w_tau == doctest::Approx(w_f).epsilon(1e-4));
    Vec3 back;
    REQUIRE(k.force(p, tau, back));
    CHECK(back.x == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(back.y == doctest::Approx(-2.0).epsilon(1e-6));
    CHECK(back.z == doctest::Approx(0.5).epsilon(1e-6));
}

TEST_CASE("falcon encoders: counts and angles convert both ways, clamped to int16") {
    FalconKinematics k;
    const double th = k.theta_of(1, 1234);
    CHECK(k.counts_of(1, th) == 1234);
    CHECK(k.theta_of(0, 0) == doctest::Approx(k.geometry().theta_offset[0]));
    CHECK(k.counts_of(0, 100.0) == 32767);
    CHECK(k.counts_of(0, -100.0) == -32768);
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
    auto m = motor_counts(pp, {0.1, -0.2, 0.0});
    CHECK(m[0] == 1000);
    CHECK(m[1] == -2000);
    CHECK(m[2] == 0);
    m = motor_counts(pp, {5.0, -5.0, 0.39999});  // 50000 and -50000 counts asked
    CHECK(m[0] == 4000);
    CHECK(m[1] == -4000);
    CHECK(m[2] == 4000);
    m = motor_counts(pp, {0.1, std::numeric_limits<double>::infinity(), 0.1});
    CHECK(m[0] == 0);
    CHECK(m[1] == 0);
    CHECK(m[2] == 0);
}
