// frame_checks.hpp — the properties the device-frame fuzz targets check, for any bytes a device
// may send: the hapio frame readers (state, info, command), the Falcon's stream reassembly and the
// Haply board's hAPI reply. Shared by the libFuzzer entry points and the portable driver ctest runs
// (fuzz_main.cpp). Each returns "" when the parser behaved, otherwise what went wrong.
//
// What "behaved" means for a frame parser: it never reads past `n` (ASan in sanitizer builds), it
// refuses or accepts without throwing, what it accepts is finite and within the protocol's ranges,
// and accepted frames pack back to bytes that unpack to the same values.
#pragma once

#include "drivers/usb/falcon_protocol.hpp"
#include "drivers/usb/hapio_protocol.hpp"
#include "drivers/usb/haply_protocol.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace contactlab::fuzz {

inline std::string check_hapio_frames(std::string_view bytes) {
    namespace h = drivers::hapio;
    const auto* d = reinterpret_cast<const std::uint8_t*>(bytes.data());
    // Copied to an exact-size heap block so ASan sees any read past the end.
    const std::vector<std::uint8_t> buf(d, d + bytes.size());
    const std::uint8_t* p = buf.empty() ? nullptr : buf.data();
    h::State s;
    if (h::unpack(p, buf.size(), s) == h::FrameError::none) {
        if (s.encoders > h::kMaxEncoders || s.analog > h::kMaxAnalog || s.motors > h::kMaxMotors)
            return "hapio state accepted with channel counts beyond the protocol's";
        std::uint8_t again[h::kStateSize];
        h::pack(s, again);
        h::State back;
        if (h::unpack(again, sizeof again, back) != h::FrameError::none || back.sequence != s.sequence ||
            back.encoder != s.encoder || back.faults != s.faults)
            return "hapio state: an accepted frame does not survive pack -> unpack";
    }
    h::Info info;
    if (h::unpack(p, buf.size(), info) == h::FrameError::none) {
        std::uint8_t again[h::kInfoSize];
        h::pack(info, again);
        h::Info back;
        if (h::unpack(again, sizeof again, back) != h::FrameError::none || back.serial != info.serial ||
            back.model != info.model)
            return "hapio info: an accepted frame does not survive pack -> unpack";
    }
    h::Command c;
    if (h::unpack(p, buf.size(), c) == h::FrameError::none && c.motors > h::kMaxMotors)
        return "hapio command accepted with more motors than the protocol has";
    return {};
}

inline std::string check_falcon_stream(std::string_view bytes) {
    namespace f = drivers::falcon;
    const std::vector<std::uint8_t> buf(bytes.begin(), bytes.end());
    f::StreamParser parser;
    int seen = 0;
    const int count = parser.feed(buf.data(), buf.size(), [&](const f::State& s) {
        (void)s;
        ++seen;
    });
    if (count != seen) return "falcon stream: feed() counted packets it did not hand over";
    // Every 16 payload bytes hold at most one packet (2 of every 64 bytes are modem status).
    if (static_cast<std::size_t>(count) > buf.size() / f::kPacketSize)
        return "falcon stream: more packets than the bytes can hold";
    return {};
}

inline std::string check_haply_reply(std::string_view bytes) {
    namespace hp = drivers::haply;
    const std::vector<std::uint8_t> buf(bytes.begin(), bytes.end());
    for (int gen : {2, 3}) {
        const hp::HaplyHardware hw = hp::hardware(gen);
        std::array<double, 2> a{-1.0, -1.0};
        const std::uint8_t id = buf.empty() ? 0 : buf[0];
        const hp::ReplyError e = hp::unpack_reply(hw, id, buf.empty() ? nullptr : buf.data(), buf.size(), a);
        if (e == hp::ReplyError::none) {
            if (!std::isfinite(a[0]) || !std::isfinite(a[1])) return "haply reply: accepted angles that are not finite";
            // The driver feeds accepted angles to the kinematics: a status, never a NaN position.
            hp::Vec p{0.5, 0.5};
            const hp::KinStatus st = hp::forward_kinematics(hw.geometry, a, p);
            if (st == hp::KinStatus::ok && (!std::isfinite(p.x) || !std::isfinite(p.y)))
                return "haply kinematics: finite angles gave a position that is not finite";
            std::array<double, 2> tau{};
            if (hp::joint_torques(hw.geometry, a, hp::Vec{1.0, -1.0}, tau) == hp::KinStatus::ok &&
                (!std::isfinite(tau[0]) || !std::isfinite(tau[1])))
                return "haply kinematics: finite angles gave torques that are not finite";
        } else if (a[0] != -1.0 || a[1] != -1.0) {
            return "haply reply: a refused reply changed the angles";
        }
        // The board's side of the framing must read any exchange-sized bytes without trouble.
        std::uint8_t out_id = 0;
        std::array<float, 2> tau{};
        hp::unpack_exchange(hw, buf.empty() ? nullptr : buf.data(), buf.size(), out_id, tau);
    }
    return {};
}

}  // namespace contactlab::fuzz
