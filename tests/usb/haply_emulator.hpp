// haply_emulator.hpp — a Haply 2DIY board emulated with umockdev: an Arduino Due (2341:003e) on
// the USB bus with a cdc_acm tty, /dev/ttyACM0, in umockdev's faked sysfs and /dev. umockdev backs
// a tty node with a pseudo-terminal: the driver opens, configures (termios) and reads/writes the
// node exactly as it would a real board's, and this class answers on the pty's other end as hAPI's
// firmware does: reset, the parameter message (recorded), and one reply of angles per exchange.
// Unplugging closes the pty's other end (the driver's tty hangs up, as a real one does when its
// USB device goes) and removes the device from sysfs and /dev; plugged back, the board is the
// next ttyACM (cdc_acm's numbering while the old tty is still open).
//
// The board runs on its own thread; its state is behind a mutex.
#pragma once

#include "drivers/usb/haply_kinematics.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace contactlab::test {

// How the emulated board answers exchanges.
enum class HaplyMisbehaviour {
    none,
    wrong_device,        // answers with another device id
    short_frames,        // answers with 5 of the 9 bytes
    nan_angles,          // answers with a NaN angle
    silent,              // does not answer
    unplug_mid_exchange, // reads the next exchange, then is unplugged before answering
};

class HaplyEmulator {
public:
    struct Config {
        int generation = 3;
        std::string serial = "HAPLY-0042";  // the USB device's iSerial
        bool plugged = true;
    };
    explicit HaplyEmulator(const Config& c);
    HaplyEmulator() : HaplyEmulator(Config{}) {}
    ~HaplyEmulator();
    HaplyEmulator(const HaplyEmulator&) = delete;
    HaplyEmulator& operator=(const HaplyEmulator&) = delete;

    void plug();
    void unplug();
    // Makes /dev/ttyACM0 unreadable for this process and its children (drops CAP_DAC_OVERRIDE).
    void deny_permission();

    // The handle at p (m, device frame): the board reports the angles that put it there.
    void set_position(drivers::haply::Vec p);
    void set_angles_deg(float a1, float a2);
    void misbehave(HaplyMisbehaviour m);

    std::uint64_t resets() const;
    std::uint64_t exchanges() const;            // exchange messages received
    std::uint64_t replies() const;              // replies sent
    std::vector<std::uint8_t> parameters() const;  // the last parameter message, whole
    std::array<float, 2> last_torques() const;  // N m, motor 1 and 2
    std::uint8_t device_id() const;             // from the parameter message
    bool plugged() const;
    std::string node() const;                   // /dev/ttyACM0, then ttyACM1 after a replug, ...

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace contactlab::test
