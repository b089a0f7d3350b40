// haply_protocol.cpp — hAPI frames (see haply_protocol.hpp).
#include "drivers/usb/haply_protocol.hpp"

#include <cmath>
#include <cstring>

namespace contactlab::drivers::haply {

namespace {

// Which motor (0 or 1) sits on the lower port: the wire carries the lower port first.
int first_motor(const HaplyHardware& hw) noexcept { return hw.actuator[0].port <= hw.actuator[1].port ? 0 : 1; }
int first_encoder(const HaplyHardware& hw) noexcept { return hw.encoder[0].port <= hw.encoder[1].port ? 0 : 1; }

std::uint8_t port_bit(std::uint8_t port) noexcept {
    return port >= 1 && port <= 4 ? static_cast<std::uint8_t>(1u << (port - 1)) : 0;
}

}  // namespace

const char* to_string(ReplyError e) noexcept {
    switch (e) {
        case ReplyError::none: return "none";
        case ReplyError::short_frame: return "short frame";
        case ReplyError::wrong_device: return "wrong device id";
        case ReplyError::not_finite: return "angle not finite";
    }
    return "unknown";
}

void put_float(std::uint8_t* out, float v) noexcept {
    std::uint32_t u = 0;
    std::memcpy(&u, &v, 4);
    for (int i = 0; i < 4; ++i) out[i] = static_cast<std::uint8_t>(u >> (8 * i));
}

float get_float(const std::uint8_t* in) noexcept {
    std::uint32_t u = 0;
    for (int i = 0; i < 4; ++i) u |= static_cast<std::uint32_t>(in[i]) << (8 * i);
    float v = 0.0f;
    std::memcpy(&v, &u, 4);
    return v;
}

void pack_reset(std::uint8_t (&out)[kResetSize]) noexcept {
    out[0] = kReset;
    out[1] = 0;
}

void pack_parameters(const HaplyHardware& hw, std::uint8_t id, std::uint8_t (&out)[kParametersSize]) noexcept {
    const int m0 = first_motor(hw), e0 = first_encoder(hw);
    std::size_t k = 0;
    out[k++] = kParameters;
    out[k++] = id;
    out[k++] = static_cast<std::uint8_t>(port_bit(hw.actuator[0].port) | port_bit(hw.actuator[1].port));
    out[k++] = hw.actuator[m0].direction;
    out[k++] = hw.actuator[1 - m0].direction;
    out[k++] = static_cast<std::uint8_t>(port_bit(hw.encoder[0].port) | port_bit(hw.encoder[1].port));
    out[k++] = hw.encoder[e0].direction;
    out[k++] = hw.encoder[1 - e0].direction;
    out[k++] = 0;  // analog inputs: none
    out[k++] = 0;  // PWM pins: none
    for (int e : {e0, 1 - e0}) {
        put_float(out + k, static_cast<float>(hw.encoder[e].offset_deg));
        put_float(out + k + 4, static_cast<float>(hw.encoder[e].counts_per_rev));
        k += 8;
    }
}

void pack_exchange(const HaplyHardware& hw, std::uint8_t id, const std::array<double, 2>& tau,
                   std::uint8_t (&out)[kExchangeSize]) noexcept {
    const int m0 = first_motor(hw);
    out[0] = kExchange;
    out[1] = id;
    const double a = tau[m0], b = tau[1 - m0];
    put_float(out + 2, std::isfinite(a) ? static_cast<float>(a) : 0.0f);
    put_float(out + 6, std::isfinite(b) ? static_cast<float>(b) : 0.0f);
}

ReplyError unpack_reply(const HaplyHardware& hw, std::uint8_t id, const std::uint8_t* data, std::size_t n,
                        std::array<double, 2>& angles) noexcept {
    if (data == nullptr || n < kReplySize) return ReplyError::short_frame;
    if (data[0] != id) return ReplyError::wrong_device;
    const float a = get_float(data + 1), b = get_float(data + 5);
    if (!std::isfinite(a) || !std::isfinite(b)) return ReplyError::not_finite;
    const int e0 = first_encoder(hw);
    angles[e0] = static_cast<double>(a) * kDegree;
    angles[1 - e0] = static_cast<double>(b) * kDegree;
    return ReplyError::none;
}

void pack_reply(const HaplyHardware& hw, std::uint8_t id, const std::array<float, 2>& angles_deg,
                std::uint8_t (&out)[kReplySize]) noexcept {
    const int e0 = first_encoder(hw);
    out[0] = id;
    put_float(out + 1, angles_deg[e0]);
    put_float(out + 5, angles_deg[1 - e0]);
}

bool unpack_exchange(const HaplyHardware& hw, const std::uint8_t* data, std::size_t n, std::uint8_t& id,
                     std::array<float, 2>& tau) noexcept {
    if (data == nullptr || n < kExchangeSize || data[0] != kExchange) return false;
    const int m0 = first_motor(hw);
    id = data[1];
    tau[m0] = get_float(data + 2);
    tau[1 - m0] = get_float(data + 6);
    return true;
}

}  // namespace contactlab::drivers::haply
