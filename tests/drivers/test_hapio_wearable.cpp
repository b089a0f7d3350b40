// test_hapio_wearable.cpp — seed 003's platform over hapio model 2 (HAPIO.md): FSR counts in,
// cable motor drives out, the estimation and PD on the host, closed around the simulated plant
// through real frames (pack/unpack), and the faults that must give zero drive.
#include "drivers/usb/hapio_wearable_model.hpp"
#include "haptics/wearable/plant.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace contactlab::drivers;
using namespace contactlab::drivers::hapio;
using namespace contactlab::wearable;

namespace {
// The board: ADC counts of the plant's FSRs, rounded, clamped to the ADC's range.
State board_state(WearablePlant& plant, const WearableCalibration& c, std::uint16_t seq) {
    State s;
    s.sequence = seq;
    s.analog = kWearableAnalog;
    s.motors = kWearableMotors;
    const Eigen::Vector3d f = plant.read_fsr();
    for (int i = 0; i < 3; ++i) {
        const double counts = std::round(std::max(0.0, f(i)) / c.fsr_newton_per_count);
        s.adc[i] = static_cast<std::uint16_t>(std::min(counts, static_cast<double>(c.adc_full_scale)));
    }
    std::uint8_t bytes[kStateSize];
    pack(s, bytes);
    State back;
    REQUIRE(unpack(bytes, kStateSize, back) == FrameError::none);
    return back;
}
Eigen::Vector3d torques_of(const Command& cmd, const MotorDef& m) {
    std::uint8_t bytes[kCommandSize];
    pack(cmd, bytes);
    Command back;
    REQUIRE(unpack(bytes, kCommandSize, back) == FrameError::none);
    return Eigen::Vector3d(unpack_motor(back.motor[0]), unpack_motor(back.motor[1]), unpack_motor(back.motor[2])) *
           m.stall_torque;
}
}  // namespace

TEST_CASE("hapio model 2: a 0.3 N cable step through frames settles within friction and ADC quantisation") {
    const WearableCalibration c;
    WearableModel model(c);
    PlantDef pd;
    WearablePlant plant(pd);
    DeviceCommand in;
    in.platform_mode = DeviceCommand::PlatformMode::wrench;
    in.platform = {0.3, 0.3, 0.3};
    for (int k = 0; k < 400; ++k) {
        Command cmd;
        REQUIRE(model.to_command(in, board_state(plant, c, static_cast<std::uint16_t>(k)), 1e-3, cmd) == WearableLinkStatus::ok);
        plant.step(torques_of(cmd, c.motor), 1e-3);
    }
    // Friction's dead band (force_control.hpp) plus half an ADC count seen through eq. 7.
    const double band = c.motor.friction_torque / (c.force.kp + holding_torque(c.motor, 1.0));
    const IkResult ik = inverse_kinematics(c.platform, plant.pose());
    for (int i = 0; i < 3; ++i) {
        const double quantum = 0.5 * c.fsr_newton_per_count / ik.cables[i].cos_theta;
        CHECK(std::abs(plant.tension()(i) - 0.3) <= 1.01 * (band + quantum));
    }
}

TEST_CASE("hapio model 2: a saturated FSR, a force above stall and NaN give zero drive") {
    const WearableCalibration c;
    WearableModel model(c);
    State s;
    s.adc = {100, c.adc_full_scale, 100, 0};
    DeviceReading r;
    model.to_reading(s, r);
    CHECK_FALSE(r.valid);
    DeviceCommand in;
    in.platform_mode = DeviceCommand::PlatformMode::wrench;
    in.platform = {0.2, 0.2, 0.2};
    Command cmd;
    cmd.motor = {123, 123, 123, 0};
    CHECK(model.to_command(in, s, 1e-3, cmd) == WearableLinkStatus::fsr_saturated);
    CHECK(cmd.motor == std::array<std::int16_t, kMaxMotors>{});
    s.adc = {30, 30, 30, 0};
    in.platform = {0.2, 5.0, 0.2};  // above the 1.54 N stall force
    CHECK(model.to_command(in, s, 1e-3, cmd) == WearableLinkStatus::fault);
    CHECK(model.control_status() == ControlStatus::fault_above_stall);
    CHECK(cmd.motor == std::array<std::int16_t, kMaxMotors>{});
    in.platform = {0.2, std::nan(""), 0.2};
    CHECK(model.to_command(in, s, 1e-3, cmd) == WearableLinkStatus::fault);
    CHECK(cmd.motor == std::array<std::int16_t, kMaxMotors>{});
    // A good command again drives the motors: 5 counts (49 mN) below a 0.2 N reference pulls in.
    s.adc = {5, 5, 5, 0};
    in.platform = {0.2, 0.2, 0.2};
    CHECK(model.to_command(in, s, 1e-3, cmd) == WearableLinkStatus::ok);
    CHECK(cmd.motors == kWearableMotors);
    CHECK(cmd.motor[0] > 0);
    CHECK(model.limits().max_force == doctest::Approx(3.0 * stall_cable_force(c.motor)));
}
