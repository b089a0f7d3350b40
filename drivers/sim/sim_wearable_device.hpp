// sim_wearable_device.hpp — "sim-wearable": seed 003's fingertip platform in simulation
// (haptics/wearable/rig.hpp) behind the Device interface.
//
// Commands (DeviceCommand::platform, by platform_mode):
//   wrench  the three cable tensions Q_r (N), what eq. 6 makes of a wrench; force control, Fig. 5
//   pose    (p_z offset from the rest pose (m, + into the pad), roll alpha, pitch beta (rad)): the
//           platform's three actuated freedoms; position control, Fig. 6
//   none    zero tensions
// Readings: DeviceReading::sensors are the three FSR forces (N). The platform measures no finger
// position: with a hand path the finger is where the path says (the wearable renders no force
// on the hand, so nothing pushes it off its path; seed 003 §1), else at the origin. The servo
// loop (drivers/servo_loop.cpp) turns its contact force into a pose command
// (haptics/wearable/contact_display.hpp). Bad commands are faults with zero output, cleared by the next good command (as
// sim-cld): non-finite values, a tension above the motors' stall force, a pose outside the
// workspace. An estimate in fault (an FSR reading out of range) is reported as io_error while it
// lasts. A device-side watchdog zeroes the tensions when no command arrives for
// `watchdog_timeout` of device time.
#pragma once

#include "drivers/device.hpp"
#include "drivers/hand_path.hpp"
#include "haptics/servo_seqlock.hpp"
#include "haptics/wearable/rig.hpp"
#include "haptics/wearable/rig_tuning.hpp"

#include <atomic>
#include <cstdint>

#include <optional>

namespace contactlab::drivers::sim {

// The platform as the UI draws it (render::PlatformDrawing), published by advance() through a
// seqlock: any thread may read it.
struct WearablePlatformView {
    bool valid = false;                 // false before open()
    double roll = 0.0;                  // rad, from the rest pose
    double press = 0.0;                 // m, p_z from the rest pose (+ into the pad)
    double pitch = 0.0;                 // rad, beta from the rest pose
    std::array<double, 3> tension{};    // N, the plant's
    std::array<double, 3> fsr{};        // N, the last readings
    double tension_limit = 0.0;         // N, the motors' stall cable force (no cable holds more)
    wearable::ControlStatus control = wearable::ControlStatus::ok;  // the PD loop's last tick
    bool position_mode = false;         // the rig's loop: position (Fig. 6) or force (Fig. 5)
};

struct SimWearableParams {
    wearable::RigDef rig = wearable::seed_fit_rig();
    double watchdog_timeout = 0.05;  // s: five periods of the 100 Hz link
};

class SimWearableDevice final : public Device {
public:
    explicit SimWearableDevice(const SimWearableParams& p = {});
    // The finger follows `path` (device time starts at the path's start).
    SimWearableDevice(const SimWearableParams& p, HandPath path);

    const char* name() const noexcept override { return "sim-wearable"; }
    DeviceCapabilities capabilities() const noexcept override;
    DeviceLimits limits() const noexcept override { return limits_; }
    bool open() override;
    void close() override;
    DeviceState state() const noexcept override { return state_; }
    DeviceFault fault() const noexcept override { return fault_; }
    void set_engaged(bool on) noexcept override;
    bool read(DeviceReading& out) noexcept override;
    void write(const DeviceCommand& cmd) noexcept override;
    void advance(double dt) noexcept override;

    // Ground truth for tests and reports (null before open()); servo thread only while it runs.
    const wearable::WearableRig* rig() const noexcept { return rig_ ? &*rig_ : nullptr; }
    // The platform for drawing, from any thread.
    WearablePlatformView platform_view() const noexcept { return view_.load(); }
    // Live gains, fit mode and FSR noise (checked by the caller: rig_tuning_problem), from any
    // thread; the servo thread applies them at its next advance(). Kept across close/open.
    void set_tuning(const wearable::RigTuning& t) noexcept {
        tuning_.store(t);
        tuning_serial_.fetch_add(1, std::memory_order_release);
    }
    wearable::RigTuning tuning() const noexcept { return tuning_.load(); }

private:
    void set_fault(DeviceFaultCode code, const char* detail) noexcept;
    SimWearableParams p_;
    std::optional<HandPath> path_;
    double t0_ = 0.0;  // s, device time at open (the path's start)
    std::optional<wearable::WearableRig> rig_;
    DeviceLimits limits_;
    DeviceState state_ = DeviceState::disconnected;
    DeviceFault fault_;
    double since_command_ = 0.0;  // s
    Seqlock<WearablePlatformView> view_;
    Seqlock<wearable::RigTuning> tuning_{wearable::tuning_of(p_.rig)};
    std::atomic<std::uint64_t> tuning_serial_{0};  // bumped by set_tuning
    std::uint64_t tuning_applied_ = 0;             // servo thread: the serial in effect
};

}  // namespace contactlab::drivers::sim
