// hapio_emulator.hpp — a hapio board emulated with umockdev, for tests that run the real libusb.
//
// umockdev fakes sysfs/udev and answers the usbfs ioctls libusb issues on the device node; this
// class implements the board's firmware behind those ioctls (HAPIO.md): the GET_INFO handshake,
// streaming state frames, applying command frames (and rejecting bad ones), kernel-driver
// binding, stalls, silence (timeouts), corrupted frames, unplug and replug through udev events.
// The handler runs on umockdev's worker thread, so all firmware state is behind a mutex.
#pragma once

#include "drivers/usb/hapio_protocol.hpp"

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>

namespace contactlab::test {

enum class Corruption { none, short_frame, bad_magic, bad_crc, bad_version, bad_counts };

class HapioEmulator {
public:
    struct Config {
        drivers::hapio::Info info{drivers::hapio::kVersion, 1, 4, 0, 3, 1000, 0x0100, 4242};
        bool kernel_driver_bound = false;  // a kernel driver holds the interface at plug-in
        double frame_period = 0.0;         // s between state frames; 0: answer every IN at once
        bool plugged = true;               // plug in at construction
    };
    explicit HapioEmulator(const Config& c);
    HapioEmulator() : HapioEmulator(Config{}) {}
    ~HapioEmulator();
    HapioEmulator(const HapioEmulator&) = delete;
    HapioEmulator& operator=(const HapioEmulator&) = delete;

    void plug();      // appears on the bus with a new address (udev "add")
    void unplug();    // every ioctl now fails with ENODEV, and udev says "remove"
    // Makes the device node unreadable for this process (drops CAP_DAC_OVERRIDE when root).
    void deny_permission();

    // Firmware inputs.
    void set_encoders(const std::array<std::int32_t, 4>& counts);
    void set_adc(const std::array<std::uint16_t, 4>& counts);  // analog channels (model 2: the FSRs)
    void set_faults(std::uint16_t faults);
    void stall_next_in();                  // the next IN transfer ends with a STALL handshake
    void set_silent(bool silent);          // stop answering IN transfers (host sees timeouts)
    void corrupt_next(Corruption c, int frames = 1);

    // Observations.
    drivers::hapio::Command last_command() const;
    std::uint64_t commands_applied() const;
    std::uint64_t commands_rejected() const;
    std::uint64_t frames_sent() const;
    std::uint64_t clear_halts() const;
    std::uint64_t discarded_urbs() const;
    bool streaming() const;
    bool kernel_driver_bound() const;
    bool motors_enabled() const;
    int bus() const { return 1; }
    int address() const;

    struct Impl;  // public for the C callback; defined in hapio_emulator.cpp

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace contactlab::test
