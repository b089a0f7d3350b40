// test_layout.cpp — the editor's layout at 1280 x 720 and larger (issue 19 item 3), in the real
// editor under xvfb-run: the menu bar, the status row, the rulers, the message row and the
// Tuning, Haptics and Plots panels cover no part of one another, stay inside the window, and
// cut no label short (no panel's content is wider than its inside). The `layout` script command
// reports Dear ImGui's own window rectangles as drawn; a snapshot at 1280 x 720 shows the status
// row clear of the canvas and rulers.
#include "process.hpp"
#include "xvfb_editor.hpp"

#include "engine/render/image.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

using namespace cli_test;
using namespace editor_test;
using namespace contactlab;

namespace {

struct Part {
    std::string name;
    double x = 0, y = 0, w = 0, h = 0;
    bool overflow = false, tiled = true;
};

// The `layout` blocks in stderr, in order: each `layout` command's lines begin with the top ruler.
std::vector<std::vector<Part>> layout_blocks(const std::string& err) {
    std::vector<std::vector<Part>> blocks;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);) {
        const std::string tag = "script layout: ";
        if (line.rfind(tag, 0) != 0) continue;
        Part p;
        const auto name_at = line.find(" name=");
        p.name = line.substr(name_at + 6);
        std::istringstream kv(line.substr(tag.size(), name_at - tag.size()));
        for (std::string w; kv >> w;) {
            const auto eq = w.find('=');
            const std::string k = w.substr(0, eq);
            const double v = std::strtod(w.c_str() + eq + 1, nullptr);
            if (k == "x") p.x = v;
            else if (k == "y") p.y = v;
            else if (k == "w") p.w = v;
            else if (k == "h") p.h = v;
            else if (k == "overflow") p.overflow = v != 0;
            else if (k == "tiled") p.tiled = v != 0;
        }
        if (p.name == "top ruler") blocks.emplace_back();
        REQUIRE_FALSE(blocks.empty());
        blocks.back().push_back(p);
    }
    return blocks;
}

const Part* named(const std::vector<Part>& parts, const std::string& name) {
    for (const Part& p : parts)
        if (p.name == name) return &p;
    return nullptr;
}

// `roller`: the device has a roller (its "roller err" plot is shown, else it must not be).
void check_block(const std::vector<Part>& parts, double width, double height, bool roller = true) {
    std::vector<std::string> names;
    for (const Part& p : parts) names.push_back(p.name);
    for (const char* want : {"##MainMenuBar", "##proxy status", "top ruler", "left ruler", "##status", "Tuning", "Haptics",
                             "Plots (last 5 s)", "scale bar", "force-scale bar", "Haptics > emergency stop"})
        CHECK_MESSAGE(std::find(names.begin(), names.end(), want) != names.end(), want);
    // Issue 29: every plot whole inside the Plots panel (none scrolled out of sight), the
    // emergency stop inside the Haptics panel; the scale bars are tiled parts below, so the
    // overlap check keeps every panel off them.
    const Part* plots = named(parts, "Plots (last 5 s)");
    REQUIRE(plots != nullptr);
    const double in_eps = 0.5;  // px
    std::vector<std::string> want_plots = {"|F|", "depth", "l_d", "period", "budget used", "time axis"};
    if (roller) want_plots.push_back("roller err");
    for (const std::string& w : want_plots) {
        const Part* q = named(parts, "Plots (last 5 s) > " + w);
        CHECK_MESSAGE(q != nullptr, w);
        if (!q) continue;
        CAPTURE(w);
        CHECK(q->h > 10.0);
        CHECK(q->x >= plots->x - in_eps);
        CHECK(q->y >= plots->y - in_eps);
        CHECK(q->x + q->w <= plots->x + plots->w + in_eps);
        CHECK(q->y + q->h <= plots->y + plots->h + in_eps);
    }
    CHECK((named(parts, "Plots (last 5 s) > roller err") != nullptr) == roller);
    // A slider's value has its own box beside the slider: the handle never covers the digits.
    int sliders = 0;
    for (const Part& sl : parts) {
        const std::string tag = "Tuning > slider ";
        if (sl.name.rfind(tag, 0) != 0) continue;
        ++sliders;
        const Part* v = named(parts, "Tuning > value " + sl.name.substr(tag.size()));
        CAPTURE(sl.name);
        REQUIRE(v != nullptr);
        CHECK(v->w > 0.0);
        CHECK(v->x >= sl.x + sl.w);  // right of the slider, not on it
    }
    CHECK(sliders >= 3);  // Ke, max force, finger R at least are on screen
    const Part* haptics = named(parts, "Haptics");
    const Part* stop = named(parts, "Haptics > emergency stop");
    if (haptics && stop) CHECK(stop->y + stop->h <= haptics->y + haptics->h + in_eps);
    // The Haptics panel's text scrolls in whole lines: its box is a whole number of rows tall and
    // inside the panel, so no line is cut by the panel's edge (the Plots panel below used to cut
    // the last one in half at 1280x720).
    const Part* text = named(parts, "Haptics > text");
    const Part* row = named(parts, "Haptics > text row");
    CHECK(text != nullptr);
    CHECK(row != nullptr);
    if (haptics && text && row) {
        REQUIRE(row->h > 10.0);
        const double rows = text->h / row->h;
        CHECK(rows >= 1.0);
        CHECK(std::abs(rows - std::round(rows)) < 1e-3);
        CHECK(text->y >= haptics->y - in_eps);
        CHECK(text->y + text->h <= haptics->y + haptics->h + in_eps);
    }
    const double eps = 0.5;  // px: shared edges are fine
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const Part& a = parts[i];
        CAPTURE(a.name);
        CHECK_FALSE(a.overflow);
        CHECK(a.x >= -eps);
        CHECK(a.y >= -eps);
        CHECK(a.x + a.w <= width + eps);
        CHECK(a.y + a.h <= height + eps);
        if (!a.tiled) continue;
        for (std::size_t j = i + 1; j < parts.size(); ++j) {
            const Part& b = parts[j];
            if (!b.tiled) continue;
            const bool overlap = a.x + eps < b.x + b.w && b.x + eps < a.x + a.w && a.y + eps < b.y + b.h && b.y + eps < a.y + a.h;
            CHECK_MESSAGE(!overlap, a.name << " overlaps " << b.name);
        }
    }
}

}  // namespace

TEST_CASE("layout: with sim-wearable and sim-cld at 1280x720 every plot and scale bar is in sight and uncovered") {
    TempDir dir;
    const std::string script = dir.file("devices.txt");
    write_text(script,
               "generate bumps\nfinger 0 5\n"
               "device sim-wearable\nkey z\nframes 5\nlayout\n"
               "device sim-cld\nframes 5\nlayout\n"
               "device mouse\nframes 5\nlayout\nquit\n");
    const auto p = run_under_xvfb({"edit", "--software", "--validation", "--width", "1280", "--height", "720",
                                   "--timeout", "60", "--script", script});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const auto blocks = layout_blocks(p.err);
    REQUIRE(blocks.size() == 3);
    check_block(blocks[0], 1280, 720, false);  // the wearable: no roller, no "roller err"
    CHECK(named(blocks[0], "platform key") != nullptr);  // the cables' colour explained, uncovered
    const Part* section = named(blocks[0], "Tuning > Wearable platform (seed 003, live)");
    const Part* tuning = named(blocks[0], "Tuning");
    REQUIRE(section != nullptr);
    REQUIRE(tuning != nullptr);
    CHECK(section->y + section->h <= tuning->y + tuning->h + 0.5);
    check_block(blocks[1], 1280, 720, true);
    check_block(blocks[2], 1280, 720, true);
}

TEST_CASE("layout: at 1280x720 and 1600x1000 no part covers another or cuts a label, every section open") {
    TempDir dir;
    const std::string shot = dir.file("layout.png"), script = dir.file("layout.txt");
    // Seed 002's bumps, the finger above them, every Tuning section open, the ellipsoid model
    // (its extra fields make the Tuning panel its longest) and an error message.
    write_text(script,
               "generate bumps\nfinger 0 5\nset model ellipsoid\nset ke 1e9\n"
               "frames 5\nscreenshot " + shot + "\nlayout\n"
               "resize 1600 1000\nframes 5\nlayout\n"
               "resize 1280 720\nframes 5\nlayout\nquit\n");
    const auto p = run_under_xvfb({"edit", "--software", "--validation", "--width", "1280", "--height", "720",
                                   "--timeout", "60", "--script", script});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(contains(p.err, "validation layers on, 0 messages"));
    const auto blocks = layout_blocks(p.err);
    REQUIRE(blocks.size() == 3);
    check_block(blocks[0], 1280, 720);
    check_block(blocks[1], 1600, 1000);
    check_block(blocks[2], 1280, 720);

    // The snapshot: the status row (under the 19 px menu bar) is one colour to the right of its
    // text: no ruler tick, grid line or scene drawn through it.
    const render::Image img = render::read_png(shot);
    REQUIRE(img.width == 1280);
    REQUIRE(img.height == 720);
    const uint8_t* ref = img.pixel(1270, 28);
    int differing = 0;
    for (int x = 700; x < 1280; ++x)
        for (int y = 21; y < 36; ++y) {
            const uint8_t* q = img.pixel(x, y);
            differing += q[0] != ref[0] || q[1] != ref[1] || q[2] != ref[2];
        }
    CHECK(differing == 0);
}
