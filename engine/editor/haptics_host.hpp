// haptics_host.hpp — which device the editor's servo drives, at which rate, and the recording.
//
// Device specs (the same words as `contactlab simulate --device`, plus the editor's mouse):
//   mouse          the cursor is x_f (default; no motor)
//   sim-cld        seed 000's arm + roller in simulation, held by a hand that follows the cursor
//   replay:FILE    a recording ("contactlab recording v1") played back, one row per tick
//   usb:hapio, usb:falcon   real devices over libusb, when one is on the bus
// Switching device or rate goes through the safety path: the running servo's last tick is
// disconnected (zero force, zero roller drive), its thread joined and the device closed; the new
// device is opened, the scene and parameters published, and a new servo started, which arms and
// ramps the force in only once the commanded force is small (haptics/safety). A device that
// fails to open leaves the mouse running and the reason in the returned message.
//
// Recording: the UI thread drains the servo's tick ring for its plots anyway; while recording it
// forwards each record into a second SPSC ring that drivers' RecordWriter drains on its own
// thread (file I/O there, never in the tick and never on the UI thread).
#pragma once

#include "haptics/parameter_limits.hpp"

#include "drivers/device.hpp"
#include "drivers/record_writer.hpp"
#include "drivers/tick_record.hpp"
#include "engine/editor/live_servo.hpp"
#include "engine/editor/pose_input.hpp"
#include "haptics/scene.hpp"
#include "haptics/spsc_ring.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace contactlab::editor {

// One entry of the device menu.
struct DeviceOption {
    std::string spec;    // what `device` / switch_device() takes ("replay:" wants a file after it)
    std::string label;   // what the menu shows
    bool available = true;
    std::string why;     // when not available: the reason (e.g. "no hapio board on the USB bus")
};

// Hz, the servo rates the editor offers: the real-time range (haptics/parameter_limits.hpp).
inline constexpr double kMinRate = limits::kMinServoRate;
inline constexpr double kMaxRate = limits::kMaxRealtimeServoRate;

class HapticsHost {
public:
    // `servo_core`: the CPU reserved for the servo thread (reserve_servo_core()), or -1.
    explicit HapticsHost(int servo_core) : core_(servo_core) {}
    ~HapticsHost();
    HapticsHost(const HapticsHost&) = delete;
    HapticsHost& operator=(const HapticsHost&) = delete;

    // Stops whatever runs (zero force first), then opens `spec` at `rate` (Hz) with the scene and
    // parameters published before the first tick. Returns an empty string on success, else why it
    // failed (bad spec, unreadable recording naming file:line, device that did not open); on
    // failure the mouse runs instead. `pose`: where the cursor is (sim-cld places its arm there).
    // With `stopped` the emergency stop carries over: the new servo is stopped from its first tick.
    std::string start(const std::string& spec, double rate, const Scene& scene, const ServoParams& params,
                      const MousePose& pose, bool stopped = false);
    // Zero force, thread joined, device closed (the editor's exit).
    void stop();

    LiveServo* servo() { return servo_.get(); }
    // Counts start()s: a new servo (which got the scene and parameters at its start) is told
    // apart from the old one by this, not by its address.
    std::uint64_t generation() const { return generation_; }
    drivers::Device* device() { return device_.get(); }
    // The device that takes the cursor's pose (mouse, sim-cld), or null (replay, USB).
    PoseInput* pose_input() { return pose_input_; }
    const std::string& spec() const { return spec_; }
    double rate() const { return rate_; }  // Hz
    // s: the servo watchdog for this device. A USB device moves a motor: a stall of a few periods
    // (at least 5 ms) zeroes its output. The mouse, sim-cld and replay take a tick's time from a
    // clock that cannot kick anyone (the simulation's own clock, or no motor at all), so they
    // allow 50 ms, which the 10-15 ms gaps Xvfb causes never reach (servo_view.hpp).
    double watchdog_timeout() const;

    // The menu: mouse, sim-cld, replay, and the known USB models with their state. The USB bus is
    // scanned on the first call and when `rescan` is set (libusb; nothing is opened or claimed).
    const std::vector<DeviceOption>& options(bool rescan = false);

    // Recording to `path` (drivers/record_writer.hpp's recording format). Returns an empty string
    // on success, else why not (e.g. the file cannot be created, naming it).
    std::string start_recording(const std::string& path);
    // Drains what is left, renames the file into place; rows written.
    drivers::RecordSummary stop_recording();
    bool recording() const { return writer_ != nullptr; }
    const std::string& recording_path() const { return record_path_; }
    std::uint64_t recorded() const { return forwarded_; }
    std::uint64_t recording_dropped() const { return rec_dropped_; }
    // UI thread: one tick record drained from the servo's ring (forwarded while recording).
    void forward(const drivers::TickRecord& r);

private:
    std::unique_ptr<drivers::Device> make_device(const std::string& spec, const MousePose& pose, std::string& error);

    int core_;
    std::unique_ptr<drivers::Device> device_;
    std::unique_ptr<LiveServo> servo_;
    PoseInput* pose_input_ = nullptr;
    std::string spec_ = "mouse";
    double rate_ = 1000.0;  // Hz
    std::vector<DeviceOption> options_;
    bool scanned_ = false;
    std::uint64_t generation_ = 0;

    std::unique_ptr<SpscRing<drivers::TickRecord>> rec_ring_;
    std::unique_ptr<drivers::RecordWriter> writer_;
    std::string record_path_;
    std::uint64_t forwarded_ = 0, rec_dropped_ = 0;
};

}  // namespace contactlab::editor
