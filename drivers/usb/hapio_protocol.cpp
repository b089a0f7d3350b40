// hapio_protocol.cpp — frame layouts of HAPIO.md §3 (little-endian, CRC-32 last).
#include "drivers/usb/hapio_protocol.hpp"

#include <cmath>
#include <cstring>

namespace contactlab::drivers::hapio {

namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
        std::uint32_t c = i;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        t[i] = c;
    }
    return t;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

void put16(std::uint8_t* p, std::uint16_t v) { p[0] = v & 0xFF; p[1] = v >> 8; }
void put32(std::uint8_t* p, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) p[i] = (v >> (8 * i)) & 0xFF;
}
std::uint16_t get16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::uint32_t get32(const std::uint8_t* p) {
    return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
           (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

// Header and trailer checks shared by the three frame kinds: the CRC covers everything before it.
// Info frames may also be version 2 (kInfoVersion2).
FrameError check(const std::uint8_t* d, std::size_t n, std::size_t size, char kind) {
    if (d == nullptr || n < size) return FrameError::short_frame;
    if (d[0] != 'H' || d[1] != static_cast<std::uint8_t>(kind)) return FrameError::bad_magic;
    if (d[2] != kVersion && !(kind == 'I' && d[2] == kInfoVersion2)) return FrameError::bad_version;
    if (crc32(d, size - 4) != get32(d + size - 4)) return FrameError::bad_crc;
    return FrameError::none;
}

bool counts_ok(int enc, int an, int mot) {
    return enc <= kMaxEncoders && an <= kMaxAnalog && mot <= kMaxMotors;
}

}  // namespace

const char* to_string(FrameError e) noexcept {
    switch (e) {
        case FrameError::none: return "ok";
        case FrameError::short_frame: return "short frame";
        case FrameError::bad_magic: return "bad magic";
        case FrameError::bad_version: return "unsupported protocol version";
        case FrameError::bad_crc: return "CRC mismatch";
        case FrameError::bad_counts: return "channel counts out of range";
        case FrameError::bad_value: return "value out of range";
    }
    return "?";
}

std::uint32_t crc32(const std::uint8_t* data, std::size_t n) noexcept {
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < n; ++i) c = kCrcTable[(c ^ data[i]) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

void pack(const Info& in, std::uint8_t (&o)[kInfoSize]) noexcept {
    std::memset(o, 0, sizeof o);
    o[0] = 'H'; o[1] = 'I'; o[2] = in.version; o[3] = in.model;
    o[4] = in.encoders; o[5] = in.analog; o[6] = in.motors;
    put16(o + 8, in.frame_rate);
    put16(o + 10, in.firmware);
    put32(o + 12, in.serial);
    if (in.version >= kInfoVersion2) put32(o + 16, in.mass_mg);  // reserved (zero) in version 1
    put32(o + 28, crc32(o, 28));
}

FrameError unpack(const std::uint8_t* d, std::size_t n, Info& out) noexcept {
    if (const FrameError e = check(d, n, kInfoSize, 'I'); e != FrameError::none) return e;
    if (!counts_ok(d[4], d[5], d[6])) return FrameError::bad_counts;
    out.version = d[2]; out.model = d[3];
    out.encoders = d[4]; out.analog = d[5]; out.motors = d[6];
    out.frame_rate = get16(d + 8);
    out.firmware = get16(d + 10);
    out.serial = get32(d + 12);
    out.mass_mg = out.version >= kInfoVersion2 ? get32(d + 16) : 0;  // version 1: reserved, ignored
    return FrameError::none;
}

void pack(const State& in, std::uint8_t (&o)[kStateSize]) noexcept {
    std::memset(o, 0, sizeof o);
    o[0] = 'H'; o[1] = 'S'; o[2] = kVersion;
    o[3] = in.encoders; o[4] = in.analog; o[5] = in.motors;
    put16(o + 6, in.sequence);
    put32(o + 8, in.time_us);
    for (int i = 0; i < kMaxEncoders; ++i) put32(o + 12 + 4 * i, static_cast<std::uint32_t>(in.encoder[i]));
    for (int i = 0; i < kMaxAnalog; ++i) put16(o + 28 + 2 * i, in.adc[i]);
    put16(o + 36, in.status);
    put16(o + 38, in.faults);
    put16(o + 40, in.ack_sequence);
    put16(o + 42, in.rejected_commands);
    put32(o + 60, crc32(o, 60));
}

FrameError unpack(const std::uint8_t* d, std::size_t n, State& out) noexcept {
    if (const FrameError e = check(d, n, kStateSize, 'S'); e != FrameError::none) return e;
    if (!counts_ok(d[3], d[4], d[5])) return FrameError::bad_counts;
    out.encoders = d[3]; out.analog = d[4]; out.motors = d[5];
    out.sequence = get16(d + 6);
    out.time_us = get32(d + 8);
    for (int i = 0; i < kMaxEncoders; ++i) out.encoder[i] = static_cast<std::int32_t>(get32(d + 12 + 4 * i));
    for (int i = 0; i < kMaxAnalog; ++i) out.adc[i] = get16(d + 28 + 2 * i);
    out.status = get16(d + 36);
    out.faults = get16(d + 38);
    out.ack_sequence = get16(d + 40);
    out.rejected_commands = get16(d + 42);
    return FrameError::none;
}

void pack(const Command& in, std::uint8_t (&o)[kCommandSize]) noexcept {
    std::memset(o, 0, sizeof o);
    o[0] = 'H'; o[1] = 'C'; o[2] = kVersion; o[3] = in.motors;
    put16(o + 4, in.sequence);
    put16(o + 6, in.flags);
    for (int i = 0; i < kMaxMotors; ++i) put16(o + 8 + 2 * i, static_cast<std::uint16_t>(in.motor[i]));
    put16(o + 16, in.watchdog_ms);
    put32(o + 28, crc32(o, 28));
}

FrameError unpack(const std::uint8_t* d, std::size_t n, Command& out) noexcept {
    if (const FrameError e = check(d, n, kCommandSize, 'C'); e != FrameError::none) return e;
    if (!counts_ok(0, 0, d[3])) return FrameError::bad_counts;
    out.motors = d[3];
    out.sequence = get16(d + 4);
    out.flags = get16(d + 6);
    for (int i = 0; i < kMaxMotors; ++i) {
        out.motor[i] = static_cast<std::int16_t>(get16(d + 8 + 2 * i));
        // The wire never carries -32768: it has no positive twin, so it is a malformed value.
        if (out.motor[i] == INT16_MIN) return FrameError::bad_value;
    }
    out.watchdog_ms = get16(d + 16);
    return FrameError::none;
}

std::int16_t pack_motor(double fraction) noexcept {
    if (!std::isfinite(fraction)) return 0;  // never a NaN to the amplifier
    const double f = fraction > 1.0 ? 1.0 : (fraction < -1.0 ? -1.0 : fraction);
    return static_cast<std::int16_t>(std::lround(f * kMotorFullScale));
}

double unpack_motor(std::int16_t v) noexcept {
    const double f = static_cast<double>(v) / kMotorFullScale;
    return f > 1.0 ? 1.0 : (f < -1.0 ? -1.0 : f);
}

}  // namespace contactlab::drivers::hapio
