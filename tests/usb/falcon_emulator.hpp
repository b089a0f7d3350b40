// falcon_emulator.hpp — a Novint Falcon (FTDI FT232, 0403:cb48) emulated with umockdev: the FTDI
// vendor requests, the modem-status bytes on every IN packet, the microcontroller's bootloader
// (probe reply, upload echo) and a stand-in for Novint's firmware that answers each command
// packet with encoder counts. The firmware is "running" only after the exact bytes given as
// `firmware` were uploaded and the port switched to the normal speed.
#pragma once

#include "drivers/usb/falcon_protocol.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace contactlab::test {

class FalconEmulator {
public:
    struct Config {
        std::vector<std::uint8_t> firmware;  // what must be uploaded
        bool firmware_running = false;       // already running at plug-in (no upload needed)
        bool bootloader_answers = true;      // false: a Falcon without its power supply
        bool kernel_driver_bound = true;     // ftdi_sio holds FTDI chips by default
        std::string serial = "FTB3X9QZ";     // the FTDI chip's serial (string descriptor 3)
    };
    explicit FalconEmulator(const Config& c);
    ~FalconEmulator();
    FalconEmulator(const FalconEmulator&) = delete;
    FalconEmulator& operator=(const FalconEmulator&) = delete;

    void plug();
    void unplug();

    void set_encoders(const std::array<std::int16_t, 3>& counts);
    void set_homed(std::uint8_t bits);
    drivers::falcon::Command last_command() const;
    std::uint64_t commands() const;
    std::uint64_t uploaded_bytes() const;
    int handshakes() const;
    bool firmware_running() const;
    bool kernel_driver_bound() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace contactlab::test
