// falcon_protocol.hpp — the Novint Falcon on the wire: its FTDI FT232 USB-serial bridge
// (0403:cb48), the set-up sequences for the bootloader and for normal running, and the 16-byte
// packets of Novint's firmware (ASCII-armoured nibbles between '<' and '>').
//
// The layout follows the community documentation of the Novint firmware (libnifalcon); the
// firmware itself is Novint's and is never shipped with ContactLab: the user supplies the file.
// Pure functions, no allocation, unit-tested at their limits.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace contactlab::drivers::falcon {

inline constexpr std::uint16_t kVendorId = 0x0403;   // FTDI
inline constexpr std::uint16_t kProductId = 0xcb48;  // Novint's product ID on the FT232
inline constexpr std::uint8_t kEndpointIn = 0x81;    // bulk IN: 2 modem-status bytes per USB packet, then data
inline constexpr std::uint8_t kEndpointOut = 0x02;   // bulk OUT: raw serial data
inline constexpr std::size_t kFtdiPacket = 64;       // full-speed bulk packet: status bytes repeat per packet
inline constexpr std::size_t kPacketSize = 16;

// One FTDI vendor control request (bmRequestType 0x40, wIndex 0 = the only port).
struct FtdiRequest {
    std::uint8_t request;
    std::uint16_t value;
    const char* what;  // for error messages
};

// FTDI requests (the FT232's vendor protocol).
inline constexpr std::uint8_t kFtdiReset = 0x00, kFtdiModemCtrl = 0x01, kFtdiFlowCtrl = 0x02, kFtdiBaudRate = 0x03,
                              kFtdiSetData = 0x04, kFtdiLatency = 0x09;

// Bootloader mode: purge, 16 ms latency, 9600 baud 8N1, no flow control, RTS low, DTR pulsed
// low then high (resets the Falcon's microcontroller into its bootloader).
inline constexpr std::array<FtdiRequest, 9> kBootloaderSetup{{
    {kFtdiReset, 1, "purge RX"},
    {kFtdiReset, 2, "purge TX"},
    {kFtdiLatency, 16, "latency timer 16 ms"},
    {kFtdiBaudRate, 0x4138, "9600 baud"},
    {kFtdiSetData, 8, "8N1"},
    {kFtdiFlowCtrl, 0, "no flow control"},
    {kFtdiModemCtrl, 0x0200, "RTS low"},
    {kFtdiModemCtrl, 0x0100, "DTR low"},
    {kFtdiModemCtrl, 0x0101, "DTR high"},
}};
// Bootloader handshake at 9600 baud: send this, expect kBootReply (optionally preceded by a 0x00).
inline constexpr std::array<std::uint8_t, 3> kBootProbe{0x0a, 0x43, 0x0d};
inline constexpr std::array<std::uint8_t, 4> kBootReply{0x0a, 0x44, 0x2c, 0x0d};
// Then DTR low and the upload speed; 'A' must be echoed before the firmware is sent.
inline constexpr std::array<FtdiRequest, 2> kUploadSetup{{
    {kFtdiModemCtrl, 0x0100, "DTR low"},
    {kFtdiBaudRate, 0x0015, "upload speed (about 140 kbaud)"},
}};
inline constexpr std::uint8_t kUploadProbe = 'A';
inline constexpr std::size_t kUploadChunk = 128;  // bytes written, then read back and compared
// Normal running: 1 ms latency, about 1.456 Mbaud, purge.
inline constexpr std::array<FtdiRequest, 4> kNormalSetup{{
    {kFtdiLatency, 1, "latency timer 1 ms"},
    {kFtdiBaudRate, 0x0002, "1.456 Mbaud"},
    {kFtdiReset, 1, "purge RX"},
    {kFtdiReset, 2, "purge TX"},
}};

// Command byte 13 bits (host -> Falcon).
inline constexpr std::uint8_t kHomingMode = 0x01;
inline constexpr std::uint8_t kLedGreen = 0x02, kLedBlue = 0x04, kLedRed = 0x08;

// Host -> Falcon: one drive value per motor (signed, firmware units) and the LED/homing bits.
struct Command {
    std::array<std::int16_t, 3> motor{};
    std::uint8_t flags = 0;
};
// Falcon -> host: one encoder count per arm, homing status (bit i: arm i homed), grip buttons.
struct State {
    std::array<std::int16_t, 3> encoder{};
    std::uint8_t homed = 0;
    std::uint8_t buttons = 0;
};

void pack(const Command& c, std::uint8_t (&out)[kPacketSize]) noexcept;
// False for anything but a well-formed packet ('<' ... '>', nibble bytes in 'A'..'P').
bool unpack(const std::uint8_t* p, std::size_t n, State& out) noexcept;

// Reassembles packets from the FTDI IN stream: drops the 2 modem-status bytes at the start of
// each 64-byte USB packet, resynchronises on '<', counts what it throws away. Fixed buffers.
class StreamParser {
public:
    // Feeds one bulk IN transfer (`n` bytes, possibly several USB packets). Calls on_packet(State)
    // for each valid packet. Returns the number of valid packets.
    template <class F>
    int feed(const std::uint8_t* data, std::size_t n, F&& on_packet) noexcept {
        int count = 0;
        for (std::size_t off = 0; off < n; off += kFtdiPacket) {
            const std::size_t end = off + kFtdiPacket < n ? off + kFtdiPacket : n;
            for (std::size_t i = off + 2; i < end; ++i) {  // the first two bytes are modem status
                State s;
                if (push(data[i], s)) {
                    on_packet(s);
                    ++count;
                }
            }
        }
        return count;
    }
    std::uint64_t malformed() const noexcept { return malformed_; }
    std::uint64_t discarded_bytes() const noexcept { return discarded_; }
    void reset() noexcept { fill_ = 0; }

private:
    bool push(std::uint8_t b, State& out) noexcept;
    std::uint8_t buf_[kPacketSize]{};
    std::size_t fill_ = 0;
    std::uint64_t malformed_ = 0, discarded_ = 0;
};

}  // namespace contactlab::drivers::falcon
