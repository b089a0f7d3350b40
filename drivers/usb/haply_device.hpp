// haply_device.hpp — the Haply 2DIY (a 2-DoF pantograph on an Arduino-class board) over its USB
// serial port and Haply's hAPI framing (haply_protocol.hpp), used in the scene's plane.
//
// open() finds the board's tty (the one named by `port`, or the first tty whose USB device has
// one of kBoardIds), opens it raw, sends hAPI's reset and the parameter message of the chosen
// generation, and checks that the board answers an exchange as the expected device. Then an
// exchange thread runs at `rate`: each period it sends the motor torques for the newest force the
// servo published and reads the angles back; the angles go through the pantograph's forward
// kinematics and the handle position is published to the servo lock-free (the Falcon's pattern:
// the device transaction paces the I/O, the servo reads the freshest sample). A reply that is
// short, from another device id or carries a NaN angle is dropped and counted; no valid reply
// within `stale_after` and the servo sees no reading (it zeroes the force). Unplugged (the tty
// hangs up): state fault(disconnected), the servo keeps running with zero force, and the thread
// reopens the port when the board comes back.
//
// Plane: the workspace's centre maps to `origin` in the world, turned by 180 degrees: the 2DIY
// lies on the table with its motors away from the user, so the scene's up is away from the user
// (device -y) and the scene's right is the user's right (device -x). Forces turn the same way.
#pragma once

#include "drivers/device.hpp"
#include "drivers/device_status.hpp"
#include "drivers/usb/haply_kinematics.hpp"
#include "drivers/usb/haply_protocol.hpp"
#include "drivers/usb/serial_port.hpp"
#include "haptics/servo_seqlock.hpp"

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

namespace contactlab::drivers::haply {

// USB ids of the Arduino-class boards the 2DIY's controller enumerates as (cdc_acm ttys). Any
// other board is named with HaplyOptions::port (--haply-port).
struct BoardId {
    std::uint16_t vendor_id, product_id;
    const char* what;
};
inline constexpr BoardId kBoardIds[] = {
    {0x2341, 0x003e, "Arduino Due native port"},
    {0x2341, 0x003d, "Arduino Due programming port"},
    {0x2341, 0x804d, "Arduino Zero native port"},
};
bool is_board_id(std::uint16_t vendor_id, std::uint16_t product_id) noexcept;

struct HaplyOptions {
    int generation = 3;            // 2 or 3 (haply_kinematics.hpp: hardware())
    std::string port;              // tty to use; "" finds the board by its USB id
    std::uint8_t device_id = 5;    // hAPI device id the board is told and must answer with
    Vec2 origin{0.0, 0.0};         // m: world point the workspace's centre maps to
    double max_force = 2.0;        // N: handle force magnitude clamp (ContactLab's, not Haply's)
    double max_torque = 0.25;      // N m: per-motor saturation after J^T (ContactLab's clamp)
    double rate = 1000.0;          // Hz: exchanges per second (hAPI's 1 kHz)
    double stale_after = 0.01;     // s: a valid reply must have arrived within this
    int reply_timeout_ms = 20;     // one exchange's reply; later is a missed exchange
    double handshake_timeout = 2.5;  // s: a board that resets when its port opens needs ~2 s
    double reopen_every = 0.2;     // s: retry period while unplugged
    // kg: the lightest effective mass at the handle, for the passivity controller. Haply publishes
    // none and none was measured here: 0 (the controller cannot act) unless the user's device
    // file gives one.
    double mass = 0.0;
};

struct HaplyStats {
    std::uint64_t exchanges = 0, replies = 0;            // sent, and answered validly
    std::uint64_t short_frames = 0, wrong_device = 0, not_finite = 0, bad_pose = 0;
    std::uint64_t timeouts = 0, disconnects = 0, reconnects = 0;
    std::uint64_t rejected() const { return short_frames + wrong_device + not_finite + bad_pose; }
};

class HaplyDevice final : public Device {
public:
    explicit HaplyDevice(const HaplyOptions& o = {});
    ~HaplyDevice() override;

    const char* name() const noexcept override { return "usb:haply"; }
    DeviceCapabilities capabilities() const noexcept override;
    DeviceLimits limits() const noexcept override;
    std::string serial() const override { return serial_; }
    bool open() override;
    void close() override;
    DeviceState state() const noexcept override { return status_.get(); }
    DeviceFault fault() const noexcept override;
    void set_engaged(bool on) noexcept override;
    bool read(DeviceReading& out) noexcept override;
    void write(const DeviceCommand& cmd) noexcept override;

    HaplyStats stats() const noexcept;
    const HaplyHardware& hardware() const noexcept { return hw_; }
    std::string port() const { return port_; }
    // World <-> device frame (m), the mapping described at the top.
    Vec2 to_world(Vec p) const noexcept;
    Vec to_device(Vec2 w) const noexcept;
    // The last torques sent (N m, motor 1 and 2; tests).
    std::array<double, 2> last_torques() const noexcept { return sent_.load(); }

private:
    struct Sample {
        Vec p;                   // m, handle in the device frame
        double rx_time = 0.0;    // s on now()'s clock
        std::uint64_t count = 0;
    };
    double now() const noexcept;
    void set_fault(DeviceFaultCode code, const char* detail) noexcept;
    void clear_fault() noexcept;
    // Exchange thread.
    bool connect(std::string& error, bool reconnect);
    bool handshake(std::string& error);
    void run() noexcept;
    void exchange_once() noexcept;
    std::array<double, 2> torques_for(const DeviceCommand& c, const std::array<double, 2>& angles) const noexcept;

    HaplyOptions opt_;
    HaplyHardware hw_;
    Vec centre_;                  // m, device frame: the workspace's centre
    double epoch_ = 0.0;
    std::string port_, serial_;
    std::string open_error_;      // why open() failed (fault details point into it until reopened)

    DeviceStatus status_;  // state and fault (device_status.hpp)
    std::atomic<bool> want_engaged_{false}, stop_{false};
    Seqlock<Sample> latest_;
    Seqlock<DeviceCommand> command_;
    Seqlock<std::array<double, 2>> sent_;
    std::atomic<std::uint64_t> exchanges_{0}, replies_{0}, short_{0}, wrong_id_{0}, nan_{0}, bad_pose_{0};
    std::atomic<std::uint64_t> timeouts_{0}, disconnects_{0}, reconnects_{0};

    serial::SerialPort tty_;      // exchange thread (and open/close before/after it)
    std::array<double, 2> angles_{};  // rad, last valid reply (exchange thread)
    bool have_angles_ = false;
    int missed_ = 0;              // consecutive exchanges without a valid reply
    std::thread thread_;
};

}  // namespace contactlab::drivers::haply
