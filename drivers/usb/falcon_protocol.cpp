// falcon_protocol.cpp — Falcon packets: '<', twelve nibbles (three little-endian int16), a flags
// byte, a spare byte, '>'; every byte between the brackets is offset by 'A' (0x41) so that the
// framing characters can never appear inside a packet.
#include "drivers/usb/falcon_protocol.hpp"

namespace contactlab::drivers::falcon {

void pack(const Command& c, std::uint8_t (&o)[kPacketSize]) noexcept {
    o[0] = '<';
    for (int m = 0; m < 3; ++m) {
        const auto v = static_cast<std::uint16_t>(c.motor[m]);
        for (int k = 0; k < 4; ++k) o[1 + 4 * m + k] = static_cast<std::uint8_t>(((v >> (4 * k)) & 0xF) + 0x41);
    }
    o[13] = static_cast<std::uint8_t>((c.flags & 0x0F) + 0x41);
    o[14] = 0x41;
    o[15] = '>';
}

bool unpack(const std::uint8_t* p, std::size_t n, State& out) noexcept {
    if (p == nullptr || n < kPacketSize || p[0] != '<' || p[15] != '>') return false;
    for (int i = 1; i <= 12; ++i)
        if (p[i] < 0x41 || p[i] > 0x50) return false;  // not a nibble
    if (p[13] < 0x41) return false;
    for (int m = 0; m < 3; ++m) {
        std::uint16_t v = 0;
        for (int k = 0; k < 4; ++k) v = static_cast<std::uint16_t>(v | ((p[1 + 4 * m + k] - 0x41) << (4 * k)));
        out.encoder[m] = static_cast<std::int16_t>(v);
    }
    const std::uint8_t f = static_cast<std::uint8_t>(p[13] - 0x41);
    out.homed = (f >> 4) & 0x07;
    out.buttons = f & 0x0F;
    return true;
}

bool StreamParser::push(std::uint8_t b, State& out) noexcept {
    if (fill_ == 0) {
        if (b != '<') {
            ++discarded_;
            return false;
        }
    } else if (b == '<') {
        // A new packet starts before the old one ended: the old one was cut short.
        ++malformed_;
        discarded_ += fill_;
        fill_ = 0;
    }
    buf_[fill_++] = b;
    if (fill_ < kPacketSize) return false;
    fill_ = 0;
    if (unpack(buf_, kPacketSize, out)) return true;
    ++malformed_;
    discarded_ += kPacketSize;
    return false;
}

}  // namespace contactlab::drivers::falcon
