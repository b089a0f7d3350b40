// hapio_protocol.hpp — ContactLab's open device protocol `hapio` (spec: drivers/usb/HAPIO.md):
// fixed-size little-endian frames with magic, version, sequence number, channel counts and a
// CRC-32, packed and checked here without any USB (pure functions, unit-tested at their limits).
//
// Nothing here allocates: the transport thread unpacks every frame it receives at 1 kHz.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace contactlab::drivers::hapio {

inline constexpr std::uint16_t kVendorId = 0x1209;   // pid.codes (open-hardware VIDs)
inline constexpr std::uint16_t kProductId = 0xC1D0;  // ContactLab hapio board (see HAPIO.md)
inline constexpr std::uint8_t kInterfaceClass = 0xFF;     // vendor specific
inline constexpr std::uint8_t kInterfaceSubclass = 0x48;  // 'H'
inline constexpr std::uint8_t kInterfaceProtocol = 0x01;
inline constexpr std::uint8_t kEndpointIn = 0x81;   // interrupt IN: state frames
inline constexpr std::uint8_t kEndpointOut = 0x01;  // interrupt OUT: command frames
inline constexpr std::uint8_t kVersion = 1;
// Info frames may be version 2: version 1's layout plus the effective mass at the finger (HAPIO.md
// §3.1), which the passivity controller needs. State and command frames stay version 1.
inline constexpr std::uint8_t kInfoVersion2 = 2;

inline constexpr std::size_t kStateSize = 64;    // one full-speed packet
inline constexpr std::size_t kCommandSize = 32;
inline constexpr std::size_t kInfoSize = 32;
inline constexpr int kMaxEncoders = 4;
inline constexpr int kMaxAnalog = 4;
inline constexpr int kMaxMotors = 4;
inline constexpr std::int16_t kMotorFullScale = 32767;  // packed motor value for +1.0 of full scale

// Vendor control requests (bmRequestType vendor | interface recipient, wIndex = interface).
enum class Request : std::uint8_t { get_info = 0x01, set_streaming = 0x02, clear_fault = 0x03 };

// Status bits in a state frame.
inline constexpr std::uint16_t kStatusStreaming = 1u << 0;
inline constexpr std::uint16_t kStatusMotorsOn = 1u << 1;
// Fault bits in a state frame: any of them means the firmware has switched its motors off.
inline constexpr std::uint16_t kFaultOvercurrent = 1u << 0;
inline constexpr std::uint16_t kFaultHostWatchdog = 1u << 1;  // no command for watchdog_ms
inline constexpr std::uint16_t kFaultEncoder = 1u << 2;
inline constexpr std::uint16_t kFaultEstop = 1u << 3;
inline constexpr std::uint16_t kFaultBadCommand = 1u << 4;    // last command frame rejected
inline constexpr std::uint16_t kFaultSupply = 1u << 5;
// Command flags.
inline constexpr std::uint16_t kCommandEnable = 1u << 0;     // motors may be driven
inline constexpr std::uint16_t kCommandClearFault = 1u << 1; // clear latched faults

// Device -> host, answered to GET_INFO.
struct Info {
    std::uint8_t version = kVersion;
    std::uint8_t model = 0;          // 1: CLD rig (seed 000), 2: wearable platform (seed 003)
    std::uint8_t encoders = 0, analog = 0, motors = 0;
    std::uint16_t frame_rate = 1000; // Hz
    std::uint16_t firmware = 0;
    std::uint32_t serial = 0;
    std::uint32_t mass_mg = 0;       // version 2: lightest effective mass at the finger, mg (0: none)
    // kg, what the board declares (version 2 with a mass), else 0.
    double mass() const noexcept { return version >= kInfoVersion2 ? 1e-6 * static_cast<double>(mass_mg) : 0.0; }
};

// Device -> host, one per frame period on the IN endpoint.
struct State {
    std::uint16_t sequence = 0;
    std::uint8_t encoders = 0, analog = 0, motors = 0;
    std::uint32_t time_us = 0;                    // device clock, wraps
    std::array<std::int32_t, kMaxEncoders> encoder{};  // counts
    std::array<std::uint16_t, kMaxAnalog> adc{};       // raw ADC counts
    std::uint16_t status = 0, faults = 0;
    std::uint16_t ack_sequence = 0;               // last command sequence applied
    std::uint16_t rejected_commands = 0;          // device-side count, wraps
};

// Host -> device, one per received state frame.
struct Command {
    std::uint16_t sequence = 0;
    std::uint8_t motors = 0;
    std::uint16_t flags = 0;
    std::array<std::int16_t, kMaxMotors> motor{};  // fraction of full scale x 32767
    std::uint16_t watchdog_ms = 20;
};

// Why a received frame was refused (each is counted by the transport).
enum class FrameError : std::uint8_t { none, short_frame, bad_magic, bad_version, bad_crc, bad_counts, bad_value };
const char* to_string(FrameError e) noexcept;

std::uint32_t crc32(const std::uint8_t* data, std::size_t n) noexcept;  // IEEE 802.3

void pack(const Info& in, std::uint8_t (&out)[kInfoSize]) noexcept;
FrameError unpack(const std::uint8_t* data, std::size_t n, Info& out) noexcept;
void pack(const State& in, std::uint8_t (&out)[kStateSize]) noexcept;
FrameError unpack(const std::uint8_t* data, std::size_t n, State& out) noexcept;
void pack(const Command& in, std::uint8_t (&out)[kCommandSize]) noexcept;
FrameError unpack(const std::uint8_t* data, std::size_t n, Command& out) noexcept;

// A motor drive as a fraction of full scale, saturated to [-1, 1] (NaN: 0), packed to int16.
std::int16_t pack_motor(double fraction) noexcept;
double unpack_motor(std::int16_t v) noexcept;

}  // namespace contactlab::drivers::hapio
