// haply_protocol.hpp — the hAPI framing a Haply board speaks over its USB serial port, packed and
// checked here without any I/O (pure functions; the fuzz target and the emulator use them too).
//
// Host -> board, every message [type, device id, bytes..., little-endian float32s...]:
//   reset      type 0, device id 0, nothing else: the board forgets its set-up.
//   parameters type 1: the actuators (a port mask, then one direction byte per used port, in
//              port order), the encoders (mask, directions), the analog inputs (count 0) and PWM
//              pins (count 0), then per used encoder port its offset (deg) and counts per turn.
//              The board does not answer it.
//   exchange   type 2: one torque (N m) per used actuator port, in port order. The board answers
//              every exchange with [device id, one angle (deg) per used encoder port] and only
//              then: the host's exchanges pace it (hAPI runs them at 1 kHz).
// The port mask has bit (port - 1) set for each port in use. Both 2DIY generations put motor 1
// on port 2 and motor 2 on port 1, so on the wire the order is (motor 2, motor 1).
//
// Nothing here allocates: the exchange thread packs and checks a frame every millisecond.
#pragma once

#include "drivers/usb/haply_kinematics.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace contactlab::drivers::haply {

inline constexpr std::uint8_t kReset = 0;
inline constexpr std::uint8_t kParameters = 1;
inline constexpr std::uint8_t kExchange = 2;

inline constexpr std::size_t kResetSize = 2;
// type, id, actuator mask + 2 directions, encoder mask + 2 directions, analog 0, pwm 0, 4 floats.
inline constexpr std::size_t kParametersSize = 2 + 3 + 3 + 1 + 1 + 4 * 4;  // 26 bytes
inline constexpr std::size_t kExchangeSize = 2 + 2 * 4;                     // 10 bytes
inline constexpr std::size_t kReplySize = 1 + 2 * 4;                        // 9 bytes

// Why a reply was refused (each is counted by the device).
enum class ReplyError : std::uint8_t { none, short_frame, wrong_device, not_finite };
const char* to_string(ReplyError e) noexcept;

void pack_reset(std::uint8_t (&out)[kResetSize]) noexcept;
// The parameter message for a 2DIY generation, as device `id`.
void pack_parameters(const HaplyHardware& hw, std::uint8_t id, std::uint8_t (&out)[kParametersSize]) noexcept;
// The exchange message: motor torques tau (N m) of motor 1 and 2, put in port order. A torque
// that is not finite is sent as 0 (NaN never reaches the board).
void pack_exchange(const HaplyHardware& hw, std::uint8_t id, const std::array<double, 2>& tau,
                   std::uint8_t (&out)[kExchangeSize]) noexcept;
// A reply of n bytes: the motor angles (rad) of motor 1 and 2 when it is whole, from device `id`
// and finite; otherwise the error and `angles` untouched.
ReplyError unpack_reply(const HaplyHardware& hw, std::uint8_t id, const std::uint8_t* data, std::size_t n,
                        std::array<double, 2>& angles) noexcept;

// The board's side, for emulators and tests: the reply to angles (deg) of motor 1 and 2, and the
// torques (N m, motor 1 and 2) an exchange message carries (false unless whole and type 2).
void pack_reply(const HaplyHardware& hw, std::uint8_t id, const std::array<float, 2>& angles_deg,
                std::uint8_t (&out)[kReplySize]) noexcept;
bool unpack_exchange(const HaplyHardware& hw, const std::uint8_t* data, std::size_t n, std::uint8_t& id,
                     std::array<float, 2>& tau) noexcept;

// Little-endian float32 (hAPI's byte order on every board).
void put_float(std::uint8_t* out, float v) noexcept;
float get_float(const std::uint8_t* in) noexcept;

}  // namespace contactlab::drivers::haply
