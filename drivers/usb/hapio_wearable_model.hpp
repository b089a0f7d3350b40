// hapio_wearable_model.hpp — how a hapio board's channels become seed 003's wearable platform
// (HAPIO.md, "Wearable platform channel assignment (model 2)"): three cable motors driven as a
// fraction of the 0615S's stall torque, three FSRs on analog inputs. The board has no encoders
// (the seed measures no cable length); the host runs the estimation of Fig. 4 and the PD of
// Fig. 5 or 6 on every state frame, so the loop closes at the board's frame rate while
// references change at the servo's (the seed's link: 100 Hz).
//
// Pure arithmetic on the transport thread: no allocation, no I/O. Not yet wired into
// HapioDevice (which drives model 1); tests/drivers/test_hapio_wearable.cpp drives it directly.
#pragma once

#include "drivers/device.hpp"
#include "drivers/usb/hapio_protocol.hpp"
#include "haptics/wearable/position_control.hpp"

namespace contactlab::drivers::hapio {

struct WearableCalibration {
    wearable::PlatformDef platform;
    wearable::Mat6 stiffness = wearable::finger_stiffness();
    wearable::MotorDef motor;                  // full scale of a motor channel: motor.stall_torque
    wearable::EstimatorDef estimator;
    wearable::ForceControlDef force;
    wearable::PositionControlDef position;
    // FSR conditioning: N per ADC count, linearised by the firmware (the FSR 400's resistance is
    // far from linear in force); 10-bit ADC spanning the estimator's 10 N.
    double fsr_newton_per_count = 10.0 / 1023.0;
    std::uint16_t adc_full_scale = 1023;       // a reading at or above it is saturated: out of range
};

// Channel assignment (HAPIO.md).
inline constexpr int kWearableMotors = 3, kWearableAnalog = 3, kWearableEncoders = 0;

enum class WearableLinkStatus : std::uint8_t {
    ok,
    fsr_saturated,        // an ADC reading at full scale: the force is unknown, output zero
    fault,                // the estimate or the controller is in fault (see control_status)
};

class WearableModel {
public:
    explicit WearableModel(const WearableCalibration& c = {});
    const WearableCalibration& calibration() const noexcept { return c_; }

    // FSR forces (N) of a frame into out.sensors; out.valid is false when a channel is saturated.
    void to_reading(const State& s, DeviceReading& out) const noexcept;

    // One state frame's control: estimate from its FSRs, then the PD on the servo's command
    // (DeviceCommand::platform as in drivers/sim/sim_wearable_device.hpp: tensions in wrench mode,
    // (p_z offset, roll, pitch) in pose mode, zero tensions for none), period dt (s) since the
    // last frame. Fills motor[0..2] of `cmd` (fractions of the stall torque) and cmd.motors.
    // Faults of any kind give zero drive.
    WearableLinkStatus to_command(const DeviceCommand& in, const State& s, double dt, Command& cmd) noexcept;

    wearable::ControlStatus control_status() const noexcept { return status_; }
    const wearable::Estimate& estimate() const noexcept { return estimate_; }
    void reset() noexcept;
    DeviceLimits limits() const noexcept;

private:
    WearableCalibration c_;
    wearable::ForceController force_;
    wearable::PositionController position_;
    wearable::Estimate estimate_;
    wearable::ControlStatus status_ = wearable::ControlStatus::ok;
};

}  // namespace contactlab::drivers::hapio
