// device.hpp — the one interface every device family implements (DESIGN.md "Devices").
//
// A device reports the finger configuration and its sensors and accepts commands. The families it
// is shaped for: the planar force arm with the CLD roller (seed 000), point-force 3-D devices used
// in a plane (e.g. a Falcon: a z force and position exist), the seed 003 wearable platform (three
// cable motors, three FSRs, platform wrench or pose commands, a 100 Hz link), the mouse, the
// scripted hand on simulated hardware, and replay of a recording.
//
// Pacing: real devices pace the servo by their transaction (exchange() blocks for one I/O round
// trip); simulated devices advance their physics in advance(dt) (virtual or real time). The servo
// calls, per tick: read() -> compute -> write(), and for simulations advance(period).
// read/write/advance are called only from the servo thread and must not allocate or lock.
#pragma once

#include "haptics/vec2.hpp"
#include "haptics/aabb_tree.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace contactlab::drivers {

enum class DeviceState : std::uint8_t { disconnected, opening, ready, engaged, fault };
const char* to_string(DeviceState s) noexcept;

// Why a device is in DeviceState::fault. `detail` is a static string (no allocation on the servo
// thread), e.g. "USB transfer timed out".
// disconnected and permission_denied were added for USB devices: unplugging and a missing udev
// rule are the two faults a user meets most, and each needs its own message and recovery.
enum class DeviceFaultCode : std::uint8_t {
    none, not_found, open_failed, io_error, timeout, watchdog, non_finite_command, over_limit, end_of_data,
    disconnected, permission_denied
};
const char* to_string(DeviceFaultCode c) noexcept;
struct DeviceFault {
    DeviceFaultCode code = DeviceFaultCode::none;
    const char* detail = "";
};

// What a device can do; the servo assembles only what is used (no roller: no roller PID).
struct DeviceCapabilities {
    bool planar_force = false;    // renders a force in the x-y plane
    bool spatial_force = false;   // 3-D point force (used in a plane; z held by a centring spring)
    bool finger_angle = false;    // measures phi (otherwise phi is fixed, e.g. the mouse)
    bool roller = false;          // CLD contact element along the pad
    bool platform = false;        // seed 003 wearable: 3 cables, platform wrench/pose commands
    int force_sensors = 0;        // e.g. 3 FSRs on the wearable
    bool simulated = false;       // physics advanced by advance(dt)
    bool paced_by_device = false; // exchange() blocks for one transaction per tick
};

// Declared limits: the UI shows stiffness against them; the servo clamps to them.
struct DeviceLimits {
    double max_force = 1.5;             // N, continuous force magnitude at the finger
    Vec2 axis_max_force{1.5, 1.5};      // N, per-axis saturation (after the magnitude clamp)
    double max_stable_stiffness = 2000; // N/m at 1 kHz (2 b / T for the declared damping)
    double damping = 1.0;               // N s/m, physical damping b at the finger (lower bound)
    // kg, the lightest effective mass at the finger (lower bound); 0: not declared. A damper
    // sampled at period T rings past 2 m / T: the passivity controller adds at most m / T.
    double mass = 0.0;
    Aabb workspace;                     // m, where the finger centre can be
    double roller_min = -0.010;         // m, roller travel (if any)
    double roller_max = 0.010;          // m
    double min_rate = 100.0;            // Hz, servo rates the device supports
    double max_rate = 20000.0;          // Hz
    double native_rate = 1000.0;        // Hz, e.g. 100 for the wearable's serial link
};

// One reading, SI. Fields a device does not have are left at their defaults.
struct DeviceReading {
    double t = 0.0;                 // s, device time of the sample
    Vec2 finger{0.0};               // x_f, m (finger centre of curvature in the plane)
    double phi = 0.0;               // rad
    double z = 0.0;                 // m, out-of-plane coordinate (3-D devices)
    double roller_l = 0.0;          // m, contact element position along the pad
    std::array<double, 3> sensors{}; // e.g. FSR forces (N) of the wearable
    bool valid = false;             // false: nothing usable this tick
};

struct DeviceCommand {
    Vec2 force{0.0};                // N on the finger, in the plane
    double force_z = 0.0;           // N, 3-D devices (plane-keeping)
    double roller_drive = 0.0;      // roller motor drive (V for the simulated CLD)
    double roller_target = 0.0;     // m, for devices that close the roller loop themselves
    std::array<double, 3> platform{}; // wearable: cable tensions (N) or platform pose, see mode
    enum class PlatformMode : std::uint8_t { none, wrench, pose } platform_mode = PlatformMode::none;
};

class Device {
public:
    virtual ~Device() = default;

    virtual const char* name() const noexcept = 0;
    virtual DeviceCapabilities capabilities() const noexcept = 0;
    virtual DeviceLimits limits() const noexcept = 0;
    // The unit's serial number as the device reports it once open (a hapio board's handshake),
    // for the provenance of what was measured with it; "" when it has none (simulated devices,
    // the mouse) or has not said yet. Never called on the servo thread (it may allocate).
    virtual std::string serial() const { return {}; }

    // Disconnected -> Opening -> Ready. May block and allocate (off the servo thread). Returns
    // false and enters Fault (with the reason) when it fails.
    virtual bool open() = 0;
    virtual void close() = 0;

    virtual DeviceState state() const noexcept = 0;
    virtual DeviceFault fault() const noexcept = 0;
    // Ready <-> Engaged: the servo engages once its safety gate opens.
    virtual void set_engaged(bool on) noexcept = 0;

    // Servo thread, once per tick. Never allocate, lock or log.
    virtual bool read(DeviceReading& out) noexcept = 0;
    virtual void write(const DeviceCommand& cmd) noexcept = 0;
    // Simulated devices: integrate the physics over dt (s). Real devices: no-op.
    virtual void advance(double dt) noexcept { (void)dt; }
};

}  // namespace contactlab::drivers
