// hapio_device.hpp — a hapio board (HAPIO.md) driving seed 000's CLD rig (model 1) or seed 003's
// wearable platform (model 2, chosen by the board's GET_INFO), behind the Device interface, over
// the libusb transport.
//
// Threads: the servo thread calls read()/write()/set_engaged() and only loads/stores lock-free
// seqlocks and atomics. All USB work (bring-up, streaming transfers, hot-plug, teardown) runs on
// the UsbContext's event thread. The board streams one state frame per millisecond; each frame
// that arrives is answered at once with the newest command the servo published, so the device's
// clock paces the USB exchange and the servo only ever sees the freshest frame (older than
// `stale_after`: no valid reading, which the servo treats as a device fault and zeroes force).
#pragma once

#include "drivers/device.hpp"
#include "drivers/device_status.hpp"
#include "drivers/usb/hapio_cld_model.hpp"
#include "drivers/usb/hapio_protocol.hpp"
#include "drivers/usb/hapio_wearable_model.hpp"
#include "drivers/usb/usb_context.hpp"
#include "haptics/servo_seqlock.hpp"

#include <array>
#include <atomic>
#include <memory>

struct libusb_device;
struct libusb_device_handle;
struct libusb_transfer;

namespace contactlab::drivers::hapio {

struct HapioOptions {
    std::uint16_t vendor_id = kVendorId;
    std::uint16_t product_id = kProductId;
    int bus = -1, address = -1;          // pick one board when several are plugged in (-1: any)
    CldCalibration calibration;
    WearableCalibration wearable;        // model 2 boards (seed 003's platform)
    double stale_after = 0.005;          // s: a newer frame must have arrived within this
    unsigned transfer_timeout_ms = 100;  // IN/OUT transfer timeout (a silent board is a fault)
    unsigned control_timeout_ms = 200;   // handshake requests
    int open_attempts = 3;               // bounded bring-up retries for transient errors
    double retry_delay = 0.05;           // s between attempts
    std::uint16_t watchdog_ms = 20;      // firmware stops its motors without a command this long
    // kg: effective mass at the finger from the user's device file, used when the board declares
    // none (a version 1 info frame); 0: none (the passivity controller cannot act).
    double mass = 0.0;
};

// Counters since construction (monotone; read from any thread).
struct HapioStats {
    std::uint64_t frames = 0;            // valid state frames
    std::uint64_t commands = 0;          // command frames the board accepted (OUT completed)
    std::uint64_t short_frames = 0, bad_magic = 0, bad_version = 0, bad_crc = 0, bad_counts = 0;
    std::uint64_t rejected() const { return short_frames + bad_magic + bad_version + bad_crc + bad_counts; }
    std::uint64_t sequence_gaps = 0;     // frames the board sent that never arrived
    std::uint64_t timeouts = 0, stalls = 0, transfer_errors = 0;
    std::uint64_t disconnects = 0, reconnects = 0;
    std::uint64_t rtt_count = 0;         // command -> acknowledging state frame round trips
    double rtt_min = 0.0, rtt_mean = 0.0, rtt_max = 0.0;  // s
    std::uint16_t board_rejected_commands = 0;  // as the board reports it
    // Faults raised, each counted however briefly it lasted: most clear on the next clean frame
    // (a millisecond), too fast for a reader polling state() to be sure of seeing them.
    std::uint64_t faults = 0;
};

class HapioDevice final : public Device {
public:
    // `ctx`: share one libusb context between devices; null creates one on open().
    explicit HapioDevice(const HapioOptions& o = {}, std::shared_ptr<usb::UsbContext> ctx = nullptr);
    ~HapioDevice() override;

    const char* name() const noexcept override { return "usb:hapio"; }
    DeviceCapabilities capabilities() const noexcept override;
    // The effective mass: the board's own (info frame version 2), else the device file's.
    DeviceLimits limits() const noexcept override {
        DeviceLimits l = is_wearable() ? wearable_.limits() : model_.limits();
        const double m = info().mass();
        l.mass = m > 0.0 ? m : opt_.mass;
        return l;
    }
    bool open() override;
    void close() override;
    DeviceState state() const noexcept override { return status_.get(); }
    DeviceFault fault() const noexcept override;
    void set_engaged(bool on) noexcept override;
    bool read(DeviceReading& out) noexcept override;
    void write(const DeviceCommand& cmd) noexcept override;

    HapioStats stats() const noexcept;
    Info info() const noexcept { return info_.load(); }
    // The board's serial from its handshake (Info::serial), in decimal; "" before the first open.
    std::string serial() const override {
        const std::uint32_t n = info().serial;
        return n ? std::to_string(n) : std::string();
    }
    const std::shared_ptr<usb::UsbContext>& context() const noexcept { return ctx_; }
    // The last valid frame (tests, diagnostics).
    State last_state() const noexcept { return latest_.load().state; }
    // The last fault raised, kept after it clears (tests, diagnostics; stats().faults counts them).
    DeviceFault last_fault() const noexcept;
    // True once a model 2 board (the wearable platform) has been opened.
    bool is_wearable() const noexcept { return board_model_.load(std::memory_order_acquire) == 2; }

private:
    struct Sample {
        State state;
        double rx_time = 0.0;            // s on this device's clock (now())
        std::uint64_t count = 0;
    };
    struct Counters;

    double now() const noexcept;         // s since construction, CLOCK_MONOTONIC
    void set_fault(DeviceFaultCode code, const char* detail) noexcept;
    void set_fault(const DeviceFault& f) noexcept { set_fault(f.code, f.detail); }
    void clear_fault_to_ready() noexcept;

    // --- event thread only (hapio_transport.cpp) ------------------------------------------------
    bool bring_up_with_retries();
    DeviceFault bring_up();
    void teardown(bool device_gone);
    void on_gone() noexcept;
    void on_in(libusb_transfer* t) noexcept;
    void on_out(libusb_transfer* t) noexcept;
    void process_frame(const std::uint8_t* data, int length) noexcept;
    void send_command(const State& s) noexcept;
    void submit_in(int i) noexcept;
    void clear_stall(unsigned char endpoint);
    static void in_callback(libusb_transfer* t);
    static void out_callback(libusb_transfer* t);
    static int hotplug_callback(struct libusb_context* ctx, libusb_device* dev, int event, void* user);

    HapioOptions opt_;
    CldModel model_;
    WearableModel wearable_;               // event thread (send_command); to_reading is const
    std::atomic<std::uint8_t> board_model_{1};
    std::uint32_t last_board_us_ = 0;      // event thread: board time of the last frame (us)
    bool have_board_us_ = false;
    std::shared_ptr<usb::UsbContext> ctx_;
    double epoch_ = 0.0;

    DeviceStatus status_;  // state and fault (device_status.hpp)
    std::atomic<DeviceFaultCode> last_fault_code_{DeviceFaultCode::none};
    std::atomic<const char*> last_fault_detail_{""};
    std::atomic<bool> wanted_{false};      // opened by the user: hot-plug may bring it back
    std::atomic<bool> want_engaged_{false};

    Seqlock<Sample> latest_;               // event thread -> servo
    Seqlock<DeviceCommand> command_;       // servo -> event thread
    Seqlock<Info> info_;
    std::unique_ptr<Counters> counters_;

    // Event-thread state.
    static constexpr int kInFlight = 2;    // IN transfers queued so no frame waits for a resubmit
    libusb_device_handle* handle_ = nullptr;
    libusb_device* dev_ = nullptr;
    int iface_ = 0;
    std::array<libusb_transfer*, kInFlight> in_{};
    std::array<bool, kInFlight> in_active_{};
    libusb_transfer* out_ = nullptr;
    bool out_active_ = false;
    bool stopping_ = false;
    bool gone_ = false;
    std::array<std::array<std::uint8_t, kStateSize>, kInFlight> in_buf_{};
    std::uint8_t out_buf_[kCommandSize]{};
    std::uint16_t out_seq_ = 0;
    std::uint16_t last_in_seq_ = 0;
    bool have_in_seq_ = false;
    std::array<double, 64> sent_at_{};     // s, per command sequence % 64, for round trips
    std::array<std::uint16_t, 64> sent_seq_{};
    std::array<bool, 64> sent_open_{};
    usb::HotplugWatch hotplug_;  // arrivals/departures of this device, while open
};

}  // namespace contactlab::drivers::hapio
