// falcon_device.hpp — a Novint Falcon over libusb (its FTDI bridge), used in the vertical plane.
//
// open() finds the Falcon, claims it (detaching ftdi_sio if bound), and checks whether Novint's
// firmware is already running; if not, it resets the microcontroller into its bootloader and
// uploads the firmware from the file the user names (never shipped with ContactLab), with bounded
// retries whose failures say what to try. Then the event thread streams: one 16-byte command per
// reply; each reply's encoders go through the delta kinematics on the event thread and the grip
// position is published to the servo lock-free. The servo's in-plane force is clamped, the
// out-of-plane restoring spring added, J^T gives arm torques, and each motor is saturated.
#pragma once

#include "drivers/device.hpp"
#include "drivers/device_status.hpp"
#include "drivers/usb/falcon_kinematics.hpp"
#include "drivers/usb/falcon_protocol.hpp"
#include "drivers/usb/usb_context.hpp"
#include "haptics/servo_seqlock.hpp"

#include <array>
#include <atomic>
#include <memory>
#include <string>

struct libusb_device;
struct libusb_device_handle;
struct libusb_transfer;

namespace contactlab::drivers::falcon {

struct FalconOptions {
    std::string firmware;            // firmware file to upload when the Falcon has none running
    int bus = -1, address = -1;      // pick one Falcon (-1: any)
    FalconGeometry geometry;
    FalconPlanarParams planar;
    double stale_after = 0.01;       // s: a newer reply must have arrived within this
    unsigned timeout_ms = 100;       // bulk transfer timeout
    int handshake_attempts = 20;     // bootloader probes before giving up
    int open_attempts = 2;           // whole bring-ups for transient USB errors
    double retry_delay = 0.05;       // s
    // kg: effective mass at the grip for the passivity controller. Novint publishes none and none
    // was measured here: 0 (the controller cannot act) unless the user's device file gives one.
    double mass = 0.0;
};

struct FalconStats {
    std::uint64_t packets = 0, commands = 0, malformed = 0, discarded_bytes = 0;
    std::uint64_t timeouts = 0, disconnects = 0, reconnects = 0, firmware_uploads = 0;
};

class FalconDevice final : public Device {
public:
    explicit FalconDevice(const FalconOptions& o = {}, std::shared_ptr<usb::UsbContext> ctx = nullptr);
    ~FalconDevice() override;

    const char* name() const noexcept override { return "usb:falcon"; }
    DeviceCapabilities capabilities() const noexcept override;
    DeviceLimits limits() const noexcept override;
    bool open() override;
    void close() override;
    DeviceState state() const noexcept override { return status_.get(); }
    DeviceFault fault() const noexcept override;
    void set_engaged(bool on) noexcept override;
    // Valid once all three arms have homed (the user moves the grip through its range once).
    bool read(DeviceReading& out) noexcept override;
    void write(const DeviceCommand& cmd) noexcept override;

    // The FTDI chip's serial number (its USB string descriptor), read at the first bring-up.
    std::string serial() const override;
    FalconStats stats() const noexcept;
    Vec3 grip() const noexcept { return latest_.load().p; }  // m, device frame

private:
    struct Sample {
        State state;
        Vec3 p;                 // m, grip in the device frame
        bool p_ok = false;
        double rx_time = 0.0;   // s
        std::uint64_t count = 0;
    };
    double now() const noexcept;
    void set_fault(DeviceFaultCode code, const char* detail) noexcept;
    void set_fault(const DeviceFault& f) noexcept { set_fault(f.code, f.detail); }

    // Event thread only (falcon_transport.cpp, falcon_bringup.cpp).
    bool bring_up_with_retries();
    DeviceFault bring_up();
    DeviceFault control(std::uint8_t request, std::uint16_t value);
    DeviceFault write_bytes(const std::uint8_t* data, int n);
    // Reads serial payload (modem-status bytes stripped) into buf until `want` bytes or `ms` pass.
    int read_payload(std::uint8_t* buf, int want, unsigned ms, DeviceFault& f);
    bool firmware_running(DeviceFault& f);
    DeviceFault upload_firmware();
    void teardown(bool device_gone);
    void on_gone() noexcept;
    void on_in(libusb_transfer* t) noexcept;
    void on_out(libusb_transfer* t) noexcept;
    void send_command() noexcept;
    static void in_callback(libusb_transfer* t);
    static void out_callback(libusb_transfer* t);
    static int hotplug_callback(struct libusb_context* ctx, libusb_device* dev, int event, void* user);

    FalconOptions opt_;
    FalconKinematics kin_;
    std::shared_ptr<usb::UsbContext> ctx_;
    double epoch_ = 0.0;

    DeviceStatus status_;  // state and fault (device_status.hpp)
    std::atomic<bool> wanted_{false};
    Seqlock<Sample> latest_;
    Seqlock<DeviceCommand> command_;
    Seqlock<std::array<char, 64>> serial_;  // event thread writes (bring-up), any thread reads
    std::atomic<std::uint64_t> commands_{0}, timeouts_{0}, disconnects_{0}, reconnects_{0}, uploads_{0};
    std::atomic<std::uint64_t> malformed_{0}, discarded_{0}, packets_{0};

    libusb_device_handle* handle_ = nullptr;
    libusb_device* dev_ = nullptr;
    libusb_transfer* in_ = nullptr;
    libusb_transfer* out_ = nullptr;
    bool in_active_ = false, out_active_ = false, stopping_ = false, gone_ = false;
    std::uint8_t in_buf_[kFtdiPacket * 4]{};
    std::uint8_t out_buf_[kPacketSize]{};
    StreamParser parser_;
    Vec3 last_p_{0.0, 0.0, 0.11};   // warm start of the forward kinematics
    double last_sent_ = 0.0;
    usb::HotplugWatch hotplug_;  // arrivals/departures of this device, while open
};

}  // namespace contactlab::drivers::falcon
