// test_wearable_panel.cpp — issue 29's "done when", in the real editor under xvfb-run: with
// `device sim-wearable` the Tuning panel has a "Wearable ..." section on screen (the `layout`
// command lists it) and no Roller PID section or "roller err" plot; `wearable_force_kp` is
// accepted, a negative one refused with the value kept (a refusal is an error in the status line,
// checked with `expect error 1`, not a failed command); after `device sim-cld` the roller's
// section and plot are back and `roller_kff` and `ff_cutoff_hz` are live and checked.
#include "process.hpp"
#include "xvfb_editor.hpp"

#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

using namespace cli_test;
using namespace editor_test;

namespace {

// The names of each `layout` block's parts (a block begins with the top ruler), and whether a
// part named `inner` ("PANEL > PART") lies inside its panel's rectangle.
struct Named {
    std::string name;
    double x = 0, y = 0, w = 0, h = 0;
};
std::vector<std::vector<Named>> blocks_of(const std::string& err) {
    std::vector<std::vector<Named>> blocks;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);) {
        const std::string tag = "script layout: ";
        if (line.rfind(tag, 0) != 0) continue;
        Named n;
        const auto at = line.find(" name=");
        n.name = line.substr(at + 6);
        std::istringstream kv(line.substr(tag.size(), at - tag.size()));
        for (std::string w; kv >> w;) {
            const auto eq = w.find('=');
            const double v = std::strtod(w.c_str() + eq + 1, nullptr);
            const std::string k = w.substr(0, eq);
            if (k == "x") n.x = v;
            else if (k == "y") n.y = v;
            else if (k == "w") n.w = v;
            else if (k == "h") n.h = v;
        }
        if (n.name == "top ruler") blocks.emplace_back();
        REQUIRE_FALSE(blocks.empty());
        blocks.back().push_back(n);
    }
    return blocks;
}
const Named* find_prefix(const std::vector<Named>& block, const std::string& prefix) {
    for (const Named& n : block)
        if (n.name.rfind(prefix, 0) == 0) return &n;
    return nullptr;
}
bool inside(const Named& part, const Named& panel) {
    const double eps = 0.5;  // px
    return part.x >= panel.x - eps && part.y >= panel.y - eps && part.x + part.w <= panel.x + panel.w + eps &&
           part.y + part.h <= panel.y + panel.h + eps;
}

}  // namespace

TEST_CASE("wearable panel: a Wearable section on screen, its gains checked, then the CLD roller's feed-forward") {
    TempDir dir;
    const std::string script = dir.file("wearable.txt");
    write_text(script,
               "device sim-wearable\n"
               "expect device sim-wearable\n"
               "frames 5\nlayout\n"
               "set wearable_force_kp 0.003\n"
               "expect error 0\n"
               "expect wearable_force_kp 0.003 1e-12\n"
               "set wearable_force_kp -0.001\n"
               "expect error 1\n"
               "expect wearable_force_kp 0.003 1e-12\n"
               "set wearable_position_kd 0.002\nexpect error 0\n"
               "set wearable_position_kd -1\nexpect error 1\nexpect wearable_position_kd 0.002 1e-12\n"
               "set wearable_force_kd 0.00002\nexpect error 0\n"
               "set wearable_position_kp 0.8\nexpect error 0\n"
               "set fsr_noise 0.002\nexpect error 0\nexpect fsr_noise 0.002 1e-12\n"
               "set fsr_noise 0.5\nexpect error 1\nexpect fsr_noise 0.002 1e-12\n"
               "set wearable_fit 0\nexpect error 0\nexpect wearable_fit 0\n"
               "frames 3\nreport wear\n"
               "device sim-cld\n"
               "expect device sim-cld\n"
               "frames 5\nlayout\n"
               "expect roller_kff 864.88 1e-9\n"
               "set roller_kff 500\nexpect error 0\nexpect roller_kff 500 1e-9\n"
               "set roller_kff -5\nexpect error 1\nexpect roller_kff 500 1e-9\n"
               "set ff_cutoff_hz 40\nexpect error 0\nexpect ff_cutoff_hz 40 1e-9\n"
               "set ff_cutoff_hz 0\nexpect error 1\nexpect ff_cutoff_hz 40 1e-9\n"
               "quit\n");
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--validation", "--width", "1280", "--height",
                                   "720", "--timeout", "60"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    CHECK(contains(p.err, "validation layers on, 0 messages"));
    // The platform holds what the section shows (sent by the editor's frame loop).
    const auto r = report(p.err, "wear");
    CHECK(std::stod(r.at("platform_force_kp")) == doctest::Approx(0.003).epsilon(1e-12));
    CHECK(std::stod(r.at("platform_force_kd")) == doctest::Approx(2e-5).epsilon(1e-12));
    CHECK(std::stod(r.at("platform_position_kp")) == doctest::Approx(0.8).epsilon(1e-12));
    CHECK(std::stod(r.at("platform_position_kd")) == doctest::Approx(0.002).epsilon(1e-12));
    CHECK(r.at("platform_seed_fit") == "0");
    CHECK(std::stod(r.at("platform_fsr_noise_n")) == doctest::Approx(0.002).epsilon(1e-12));
    const auto blocks = blocks_of(p.err);
    REQUIRE(blocks.size() == 2);

    // sim-wearable: its section in the Tuning panel, inside it; no roller section or plot.
    const auto& wear = blocks[0];
    const Named* tuning = find_prefix(wear, "Tuning");
    const Named* section = find_prefix(wear, "Tuning > Wearable");
    REQUIRE(tuning != nullptr);
    REQUIRE(section != nullptr);
    CHECK(inside(*section, *tuning));
    CHECK(section->h > 0.0);
    CHECK(find_prefix(wear, "Tuning > Roller") == nullptr);
    CHECK(find_prefix(wear, "Plots (last 5 s) > roller err") == nullptr);
    CHECK(find_prefix(wear, "Plots (last 5 s) > |F|") != nullptr);

    // sim-cld: the roller's section and plot, no wearable section.
    const auto& cld = blocks[1];
    CHECK(find_prefix(cld, "Tuning > Wearable") == nullptr);
    CHECK(find_prefix(cld, "Tuning > Roller PID") != nullptr);
    CHECK(find_prefix(cld, "Plots (last 5 s) > roller err") != nullptr);
}
