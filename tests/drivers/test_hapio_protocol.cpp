// test_hapio_protocol.cpp — hapio frames and the CLD channel mapping at their limits (no USB).
#include "drivers/usb/hapio_cld_model.hpp"
#include "drivers/usb/hapio_protocol.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace contactlab;
using namespace contactlab::drivers;
using namespace contactlab::drivers::hapio;

TEST_CASE("hapio crc32 is IEEE 802.3 (check value of \"123456789\")") {
    const char* s = "123456789";
    CHECK(crc32(reinterpret_cast<const std::uint8_t*>(s), 9) == 0xCBF43926u);
}

TEST_CASE("hapio state frame round-trips at the extremes of every field") {
    State s;
    s.sequence = 0xFFFF;
    s.encoders = 4;
    s.analog = 4;
    s.motors = 4;
    s.time_us = 0xFFFFFFFFu;
    s.encoder = {std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max(), -1, 0};
    s.adc = {0, 0xFFFF, 1, 0x8000};
    s.status = kStatusStreaming | kStatusMotorsOn;
    s.faults = 0xFFFF;
    s.ack_sequence = 0x1234;
    s.rejected_commands = 0xFFFF;
    std::uint8_t buf[kStateSize];
    pack(s, buf);
    CHECK(buf[0] == 'H');
    CHECK(buf[1] == 'S');
    CHECK(buf[2] == kVersion);
    State r;
    REQUIRE(unpack(buf, sizeof buf, r) == FrameError::none);
    CHECK(r.sequence == 0xFFFF);
    CHECK(r.time_us == 0xFFFFFFFFu);
    CHECK(r.encoder == s.encoder);
    CHECK(r.adc == s.adc);
    CHECK(r.status == s.status);
    CHECK(r.faults == 0xFFFF);
    CHECK(r.ack_sequence == 0x1234);
    CHECK(r.rejected_commands == 0xFFFF);
}

TEST_CASE("hapio frames: short, bad magic, bad version, bad CRC and bad counts are each refused") {
    State s;
    s.encoders = 4;
    s.motors = 3;
    std::uint8_t good[kStateSize];
    pack(s, good);
    State r;
    CHECK(unpack(good, kStateSize - 1, r) == FrameError::short_frame);
    CHECK(unpack(nullptr, 0, r) == FrameError::short_frame);
    std::uint8_t b[kStateSize];
    std::memcpy(b, good, sizeof b);
    b[1] = 'C';  // a command frame's magic on the IN endpoint
    CHECK(unpack(b, sizeof b, r) == FrameError::bad_magic);
    std::memcpy(b, good, sizeof b);
    b[2] = 2;
    CHECK(unpack(b, sizeof b, r) == FrameError::bad_version);
    for (std::size_t i = 3; i < kStateSize; ++i) {  // any single flipped bit after the header
        std::memcpy(b, good, sizeof b);
        b[i] ^= 0x01;
        CHECK(unpack(b, sizeof b, r) == FrameError::bad_crc);
    }
    std::memcpy(b, good, sizeof b);
    b[3] = 5;  // five encoders: more than a frame holds
    const std::uint32_t c = crc32(b, 60);
    std::memcpy(b + 60, &c, 4);  // little-endian host
    CHECK(unpack(b, sizeof b, r) == FrameError::bad_counts);
}

TEST_CASE("hapio command frame round-trips, and -32768 (no positive twin) is refused") {
    Command c;
    c.sequence = 7;
    c.motors = 3;
    c.flags = kCommandEnable | kCommandClearFault;
    c.motor = {kMotorFullScale, -kMotorFullScale, 0, 1};
    c.watchdog_ms = 0xFFFF;
    std::uint8_t buf[kCommandSize];
    pack(c, buf);
    Command r;
    REQUIRE(unpack(buf, sizeof buf, r) == FrameError::none);
    CHECK(r.sequence == 7);
    CHECK(r.flags == c.flags);
    CHECK(r.motor == c.motor);
    CHECK(r.watchdog_ms == 0xFFFF);
    c.motor[3] = std::numeric_limits<std::int16_t>::min();
    pack(c, buf);
    CHECK(unpack(buf, sizeof buf, r) == FrameError::bad_value);
}

TEST_CASE("pack_motor saturates at full scale and turns NaN/Inf into zero") {
    CHECK(pack_motor(0.0) == 0);
    CHECK(pack_motor(1.0) == 32767);
    CHECK(pack_motor(-1.0) == -32767);
    CHECK(pack_motor(1.0000001) == 32767);
    CHECK(pack_motor(-7.5) == -32767);
    CHECK(pack_motor(0.5) == 16384);  // 16383.5 rounds away from zero
    CHECK(pack_motor(std::nan("")) == 0);
    CHECK(pack_motor(std::numeric_limits<double>::infinity()) == 0);
    CHECK(unpack_motor(32767) == doctest::Approx(1.0));
    CHECK(unpack_motor(-32767) == doctest::Approx(-1.0));
}

namespace {
// Joint angles placing the default rig's endpoint at x (one IK branch).
void ik(const CldCalibration& c, Vec2 x, double& q1, double& q2) {
    const Vec2 d = x - c.base;
    const double c2 = (glm::dot(d, d) - c.l1 * c.l1 - c.l2 * c.l2) / (2.0 * c.l1 * c.l2);
    q2 = -std::acos(c2);
    q1 = std::atan2(d.y, d.x) - std::atan2(c.l2 * std::sin(q2), c.l1 + c.l2 * std::cos(q2));
}
}  // namespace

TEST_CASE("CLD model: encoder counts give the finger position, angle and roller in SI") {
    CldModel m;
    const CldCalibration& c = m.calibration();
    State s;
    s.encoders = 4;
    s.motors = 3;
    s.encoder = {static_cast<std::int32_t>(c.joint_counts / 4), 0, static_cast<std::int32_t>(c.angle_counts / 8),
                 static_cast<std::int32_t>(0.005 * c.roller_counts_per_m)};
    DeviceReading r;
    m.to_reading(s, r);
    // Shoulder at 90 deg, elbow straight: the arm points up from the base.
    CHECK(r.finger.x == doctest::Approx(c.base.x).epsilon(1e-12));
    CHECK(r.finger.y == doctest::Approx(c.base.y + c.l1 + c.l2));
    CHECK(r.phi == doctest::Approx(kTwoPi / 8));
    CHECK(r.roller_l == doctest::Approx(0.005));
    CHECK(r.valid);
}

TEST_CASE("CLD model: a force inside the limits is rendered exactly (J^T F then back)") {
    CldModel m;
    double q1 = 0.0, q2 = 0.0;
    ik(m.calibration(), Vec2{0.03, 0.02}, q1, q2);
    REQUIRE(m.endpoint(q1, q2).x == doctest::Approx(0.03));
    DeviceCommand in;
    in.force = Vec2{0.3, -0.4};
    in.roller_drive = 6.0;
    Command cmd;
    m.to_command(in, q1, q2, cmd);
    CHECK(cmd.motors == 3);
    const Vec2 f = m.force_of(cmd, q1, q2);
    CHECK(f.x == doctest::Approx(0.3).epsilon(1e-3));
    CHECK(f.y == doctest::Approx(-0.4).epsilon(1e-3));
    CHECK(cmd.motor[kMotorRoller] == 16384);  // 6 V of 12 V
}

TEST_CASE("CLD model: force magnitude clamped to 1.5 N first, direction kept") {
    CldModel m;
    double q1 = 0.0, q2 = 0.0;
    ik(m.calibration(), Vec2{0.0, 0.0}, q1, q2);
    DeviceCommand in;
    in.force = Vec2{0.0, 30.0};  // 20x the limit, straight up
    Command cmd;
    m.to_command(in, q1, q2, cmd);
    const Vec2 f = m.force_of(cmd, q1, q2);
    CHECK(glm::length(f) == doctest::Approx(1.5).epsilon(1e-3));
    CHECK(f.x == doctest::Approx(0.0).epsilon(1e-3));
}

TEST_CASE("CLD model: then each motor saturated to its full scale") {
    CldCalibration c;
    c.max_torque = 0.1;  // weak motors: 1.5 N at ~0.27 m of lever needs more than 0.1 N m
    CldModel m(c);
    double q1 = 0.0, q2 = 0.0;
    ik(c, Vec2{0.1, 0.0}, q1, q2);
    DeviceCommand in;
    in.force = Vec2{1.5, 0.0};
    in.roller_drive = -100.0;  // far beyond the 12 V rail
    Command cmd;
    m.to_command(in, q1, q2, cmd);
    const bool any_saturated = std::abs(cmd.motor[kMotorShoulder]) == kMotorFullScale ||
                               std::abs(cmd.motor[kMotorElbow]) == kMotorFullScale;
    CHECK(any_saturated);
    CHECK(std::abs(cmd.motor[kMotorShoulder]) <= kMotorFullScale);
    CHECK(std::abs(cmd.motor[kMotorElbow]) <= kMotorFullScale);
    CHECK(cmd.motor[kMotorRoller] == -kMotorFullScale);
}

TEST_CASE("CLD model: NaN force or roller drive never reaches the motors") {
    CldModel m;
    double q1 = 0.0, q2 = 0.0;
    ik(m.calibration(), Vec2{0.0, 0.0}, q1, q2);
    DeviceCommand in;
    in.force = Vec2{std::nan(""), 1.0};
    in.roller_drive = std::numeric_limits<double>::infinity();
    Command cmd;
    m.to_command(in, q1, q2, cmd);
    CHECK(cmd.motor[kMotorShoulder] == 0);
    CHECK(cmd.motor[kMotorElbow] == 0);
    CHECK(cmd.motor[kMotorRoller] == 0);
}
