// fuzz_targets.hpp — every fuzz target by name: its check (a property that must hold for any
// bytes) and its seeds (valid inputs built by the protocol's own packers, so a target has a
// corpus even where none is stored). The scene loader's seeds are the stored corpus only.
#pragma once

#include "frame_checks.hpp"
#include "scene_loader_check.hpp"
#ifdef CONTACTLAB_FUZZ_FILES
#include "file_checks.hpp"
#endif

#include <string>
#include <string_view>
#include <vector>

namespace contactlab::fuzz {

struct Target {
    const char* name;
    std::string (*check)(std::string_view);
    std::vector<std::string> (*seeds)();
};

inline std::vector<std::string> no_seeds() { return {}; }

inline std::vector<std::string> hapio_seeds() {
    namespace h = drivers::hapio;
    std::vector<std::string> out;
    h::State s;
    s.encoders = 4;
    s.analog = 3;
    s.motors = 3;
    s.sequence = 77;
    s.encoder = {100, -200, 300, -400};
    std::uint8_t st[h::kStateSize];
    h::pack(s, st);
    out.emplace_back(reinterpret_cast<const char*>(st), sizeof st);
    h::Info info;
    info.model = 2;
    info.encoders = 2;
    info.analog = 3;
    info.motors = 3;
    info.serial = 4242;
    std::uint8_t in[h::kInfoSize];
    h::pack(info, in);
    out.emplace_back(reinterpret_cast<const char*>(in), sizeof in);
    h::Command c;
    c.motors = 2;
    c.motor = {1000, -1000, 0, 0};
    std::uint8_t cm[h::kCommandSize];
    h::pack(c, cm);
    out.emplace_back(reinterpret_cast<const char*>(cm), sizeof cm);
    return out;
}

inline std::vector<std::string> falcon_seeds() {
    namespace f = drivers::falcon;
    f::Command c;
    c.motor = {100, -100, 2000};
    std::uint8_t p[f::kPacketSize];
    f::pack(c, p);
    // One USB packet: two modem-status bytes, then the 16-byte packet.
    std::string usb = std::string("\x31\x60", 2) + std::string(reinterpret_cast<const char*>(p), sizeof p);
    return {usb, usb + usb.substr(2)};
}

inline std::vector<std::string> haply_seeds() {
    namespace hp = drivers::haply;
    std::vector<std::string> out;
    std::uint8_t r[hp::kReplySize];
    hp::pack_reply(hp::hardware(3), 5, {150.0f, 30.0f}, r);
    out.emplace_back(reinterpret_cast<const char*>(r), sizeof r);
    std::uint8_t e[hp::kExchangeSize];
    hp::pack_exchange(hp::hardware(3), 5, {0.1, -0.1}, e);
    out.emplace_back(reinterpret_cast<const char*>(e), sizeof e);
    return out;
}

#ifdef CONTACTLAB_FUZZ_FILES
inline std::vector<std::string> results_seeds() {
    return {"trial,participant,stimulus,response,valid\n1,P1,10,20,1\n2,P1,\"1,5\",\"a\nb\",0\n"};
}
#endif

inline const Target kTargets[] = {
    {"scene", &check_scene_input, &no_seeds},
    {"hapio", &check_hapio_frames, &hapio_seeds},
    {"falcon", &check_falcon_stream, &falcon_seeds},
    {"haply", &check_haply_reply, &haply_seeds},
#ifdef CONTACTLAB_FUZZ_FILES
    {"protocol", &check_protocol_input, &no_seeds},  // corpus: scenes/experiments/*.json
    {"results", &check_results_input, &results_seeds},
#endif
};

inline const Target* find_target(std::string_view name) {
    for (const Target& t : kTargets)
        if (name == t.name) return &t;
    return nullptr;
}

}  // namespace contactlab::fuzz
