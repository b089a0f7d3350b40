// test_edit_command.cpp — the real `contactlab edit`: under `xvfb-run -a` (a screenshot read back
// from the swapchain; a scripted session that draws, touches, tunes, undoes and saves) and with
// no display at all (the message and exit code 2). Lavapipe and validation layers throughout.
#include "engine/render/image.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/stimuli.hpp"
#include "process.hpp"
#include "xvfb_editor.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <thread>

using namespace cli_test;
using namespace contactlab;

namespace {
std::size_t segment_count_of(const Scene& s) {
    std::size_t n = 0;
    for (const Contour& c : s.contours) n += c.segments.size();
    return n;
}
}  // namespace

namespace {

// `xvfb-run -a contactlab ARGS...` (Debian package xvfb); lavapipe, so pictures are CPU-rendered.
using editor_test::run_under_xvfb;

// The figure "... first frame presented N ms after start" from stderr, or -1.
double window_open_ms(const std::string& err) {
    const auto at = err.find("first frame presented ");
    if (at == std::string::npos) return -1.0;
    return std::atof(err.c_str() + at + std::strlen("first frame presented "));
}

// `contactlab edit --script SCRIPT` on an untitled scene under Xvfb (its recovery file goes to
// DIR), which must run every line and quit with 0.
ProcessResult run_script_untitled(const TempDir& dir, const std::string& script) {
    setenv("TMPDIR", dir.path().c_str(), 1);
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--validation", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    return p;
}

}  // namespace

TEST_CASE("no display: exit 2 with a message naming xvfb-run and the headless subcommands") {
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    for (const std::vector<std::string>& args : {std::vector<std::string>{"edit", scene("block.json")},
                                                 std::vector<std::string>{}}) {
        CAPTURE(args.size());
        const auto p = run_contactlab(args);
        INFO("stderr: " << p.err);
        CHECK(p.exit_code == 2);
        CHECK(contains(p.err, "no display"));
        CHECK(contains(p.err, "DISPLAY is not set"));
        CHECK(contains(p.err, "xvfb-run -a contactlab edit"));
        for (const char* sub : {"contactlab trace", "contactlab simulate", "contactlab render", "contactlab generate"})
            CHECK(contains(p.err, sub));
    }
}

TEST_CASE("--frames 3 --screenshot writes the swapchain image at the window's size") {
    TempDir dir;
    const std::string png = dir.file("shot.png");
    const auto p = run_under_xvfb({"edit", scene("block.json"), "--frames", "3", "--screenshot", png, "--width", "640",
                                   "--height", "400", "--software", "--validation", "--timeout", "100"});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(contains(p.err, "validation layers on, 0 messages"));
    CHECK(contains(p.err, "3 frames"));
    const render::Image img = render::read_png(png);
    CHECK(img.width == 640);
    CHECK(img.height == 400);
    // Real content, not a cleared image: the scene (grid, solid, finger) and ImGui's panels.
    std::set<uint32_t> colours;
    for (int y = 0; y < img.height; y += 3)
        for (int x = 0; x < img.width; x += 3) {
            const uint8_t* q = img.pixel(x, y);
            colours.insert(q[0] | q[1] << 8 | q[2] << 16);
        }
    CHECK(colours.size() > 50);
    // ImGui's dark menu bar (MenuBarBg 0.14 grey) along the top edge, right of the menus' text.
    const uint8_t* bar = img.pixel(630, 2);
    CHECK(bar[0] == 36);
    CHECK(bar[1] == 36);
    CHECK(bar[2] == 36);
    // Under xvfb-run the X server is a local Xvfb: with two CPUs or more it is kept off the servo's
    // (x_server_affinity.hpp), and the line says which.
    if (std::thread::hardware_concurrency() >= 2) {
        CHECK(contains(p.err, "contactlab edit: Xvfb (pid "));
        CHECK(contains(p.err, "kept off the servo's CPU"));
        CHECK_FALSE(contains(p.err, "refused"));
    }
    const double open_ms = window_open_ms(p.err);
    MESSAGE("window open (first frame presented) after " << open_ms << " ms");
    CHECK(open_ms > 0.0);
    CHECK(open_ms < 5000.0);  // 0.6 s measured on an idle machine; generous under parallel builds
}

TEST_CASE("scripted session: draw a line, touch it with the finger, change Ke, undo, save") {
    TempDir dir;
    const std::string saved = dir.file("drawn.json");
    const std::string shot = dir.file("contact.png");
    const std::string script = dir.file("session.txt");
    write_text(script,
               "# A new scene: a floor 80 mm long drawn left to right (solid below), mm grid snapping.\n"
               "set snap_mm 1\n"
               "tool line\n"
               "click -40 0\n"
               "click 40 0\n"
               "rclick 40 0\n"
               "expect segments 1\n"
               "expect valid 1\n"
               "# The finger (R 26 mm) above the floor: free space, the servo arms and ramps in.\n"
               "finger 0 40 0\n"
               "wait_state engaged 5\n"
               "expect contact 0\n"
               "# 1 mm into the floor: contact, |F| = Ke * 1 mm = 1 N.\n"
               "finger 0 25 0\n"
               "wait_contact 3\n"
               "wait 0.1\n"
               "expect contact 1\n"
               "expect force_above 0.9\n"
               "expect force_below 1.1\n"
               "screenshot " + shot + "\n"
               "set ke 400\n"
               "wait 0.1\n"
               "expect ke_effective 400\n"
               "expect force_below 0.45\n"
               "undo\n"
               "expect ke 1000\n"
               "wait 0.1\n"
               "expect ke_effective 1000\n"
               "save " + saved + "\n"
               "expect error 0\n"
               "expect dirty 0\n"
               "# Emergency stop: output zero at once, and it stays stopped.\n"
               "key space\n"
               "wait 0.05\n"
               "expect stopped 1\n"
               "expect state idle\n"
               "expect force_below 0.000001\n"
               "quit\n");
    setenv("TMPDIR", dir.path().c_str(), 1);  // where an untitled scene's recovery file would go
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--validation", "--timeout", "100"}, dir.path().string());
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    // Everything was saved before quitting: no recovery file left behind.
    CHECK_FALSE(std::filesystem::exists(dir.file("contactlab-untitled.recovery.json")));
    CHECK(contains(p.err, "validation layers on, 0 messages"));
    CHECK_FALSE(contains(p.err, "FAILED"));
    CHECK(contains(p.err, "ok: contact = 1"));

    // The saved scene: the drawn floor exactly, Ke back to 1000 N/m after the undo.
    const Scene s = load_scene_file(saved);
    REQUIRE(s.contours.size() == 1);
    REQUIRE(s.contours[0].segments.size() == 1);
    const auto& line = std::get<LineSegment>(s.contours[0].segments[0]);
    CHECK(line.from.x == doctest::Approx(-0.040).epsilon(1e-12));
    CHECK(line.from.y == doctest::Approx(0.0));
    CHECK(line.to.x == doctest::Approx(0.040).epsilon(1e-12));
    CHECK(line.to.y == doctest::Approx(0.0));
    CHECK_FALSE(s.contours[0].closed);
    CHECK(s.force.stiffness == 1000.0);
    CHECK(s.force.max_force == 1.5);
    // The screenshot taken in contact exists at the default window size.
    const render::Image img = render::read_png(shot);
    CHECK(img.width == 1280);
    CHECK(img.height == 720);
}

TEST_CASE("invalid geometry is explained and not saved, undo brings the valid scene back") {
    TempDir dir;
    const std::string saved = dir.file("never.json");
    const std::string script = dir.file("invalid.txt");
    write_text(script,
               "set snap_mm 1\n"
               "tool line\n"
               "click -20 0\n"
               "click 20 0\n"
               "rclick 20 0\n"
               "tool select\n"
               "# Drag the end onto the start: a zero-length line.\n"
               "drag 20 0 -20 0\n"
               "expect valid 0\n"
               "save " + saved + "\n"
               "expect error 1\n"
               "undo\n"
               "expect valid 1\n"
               "expect segments 1\n"
               "quit\n");
    run_script_untitled(dir, script);
    CHECK_FALSE(std::filesystem::exists(saved));
    // Quitting with unsaved work writes it to the recovery file: the valid line after the undo.
    const std::string rec = dir.file("contactlab-untitled.recovery.json");
    REQUIRE(std::filesystem::exists(rec));
    const Scene r = load_scene_file(rec);
    REQUIRE(r.contours.size() == 1);
    CHECK(std::get<LineSegment>(r.contours[0].segments[0]).from.x == doctest::Approx(-0.020).epsilon(1e-12));
}

namespace {
// Pixels drawn in the canvas's colour for invalid geometry (canvas.cpp: 235, 70, 60), within 3
// levels: the outline of an invalid shape and the ring at a crossing are drawn in it, nothing else.
int invalid_mark_pixels(const render::Image& img) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const std::uint8_t* p = img.pixel(x, y);
            n += std::abs(p[0] - 235) <= 3 && std::abs(p[1] - 70) <= 3 && std::abs(p[2] - 60) <= 3;
        }
    return n;
}
}  // namespace

TEST_CASE("a shape that crosses itself may be drawn: marked in red, kept from the servo, not saved") {
    TempDir dir;
    const std::string saved = dir.file("never.json"), bad = dir.file("bad.png"), good = dir.file("good.png");
    const std::string script = dir.file("bowtie.txt");
    write_text(script,
               "set snap_mm 1\n"
               "tool line\n"
               "# A zig-zag that crosses itself: an open chain, valid while it is being drawn.\n"
               "click 0 0\nclick 20 20\nclick 20 0\nclick 0 20\n"
               "expect valid 1\n"
               "# Back to the start: the chain closes into a bow-tie, which is not a solid.\n"
               "click 0 0\nrclick 0 0\n"
               "expect contours 1\nexpect segments 4\nexpect valid 0\n"
               "frames 2\nscreenshot " + bad + "\n"
               "save " + saved + "\n"
               "expect error 1\n"
               "undo\n"
               "expect valid 1\nexpect segments 3\n"
               "frames 2\nscreenshot " + good + "\n"
               "quit\n");
    const auto p = run_script_untitled(dir, script);
    CHECK(contains(p.err, "validation layers on, 0 messages"));
    CHECK_FALSE(std::filesystem::exists(saved));
    // The bow-tie's outline and the ring at its crossing in red; none once undone.
    const int red = invalid_mark_pixels(render::read_png(bad)), after = invalid_mark_pixels(render::read_png(good));
    MESSAGE(red, " red pixels with the bow-tie, ", after, " after undo");
    CHECK(red > 100);
    CHECK(after < 5);
}

TEST_CASE("resizing the window recreates the swapchain and the frames follow the new size") {
    TempDir dir;
    const std::string a = dir.file("a.png"), b = dir.file("b.png");
    const std::string script = dir.file("resize.txt");
    write_text(script, "resize 800 500\nframes 5\nscreenshot " + a + "\nresize 1000 640\nframes 5\nscreenshot " + b +
                           "\nfit\nframes 2\nquit\n");
    const auto p = run_under_xvfb({"edit", cli_test::scene("bowl.json"), "--script", script, "--software", "--validation",
                                   "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK(contains(p.err, "validation layers on, 0 messages"));
    const render::Image ia = render::read_png(a), ib = render::read_png(b);
    CHECK(ia.width == 800);
    CHECK(ia.height == 500);
    CHECK(ib.width == 1000);
    CHECK(ib.height == 640);
    const auto at = p.err.find("swapchain recreated ");
    REQUIRE(at != std::string::npos);
    CHECK(std::atoi(p.err.c_str() + at + std::strlen("swapchain recreated ")) >= 2);
}

TEST_CASE("a scene that does not load: exit 2 naming the problem when nobody watches the window") {
    TempDir dir;
    const std::string bad = dir.file("bad.json");
    write_text(bad, R"({"version": 1, "contours": [{"closed": false, "segments": [)"
                    R"({"type": "line", "from": [0, 0], "to": [0, 0]}]}]})");
    const auto p = run_under_xvfb({"edit", bad, "--frames", "2", "--software"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "contours[0].segments[0]"));
}

TEST_CASE("drawing tools: a line, a three-point arc and a quadratic curve in one chain") {
    TempDir dir;
    const std::string saved = dir.file("chain.json");
    const std::string script = dir.file("chain.txt");
    write_text(script,
               "set snap_mm 1\n"
               "tool line\nclick -30 0\nclick -10 0\nrclick -10 0\n"
               "tool arc\nclick -10 0\nclick 0 10\nclick 10 0\nrclick 10 0\n"
               "tool quad\nclick 10 0\nclick 20 -10\nclick 30 0\nrclick 30 0\n"
               "expect segments 3\nexpect contours 1\nexpect valid 1\n"
               "save " + saved + "\nexpect error 0\nquit\n");
    setenv("TMPDIR", dir.path().c_str(), 1);
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--validation", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    const Scene s = load_scene_file(saved);
    REQUIRE(s.contours.size() == 1);
    REQUIRE(s.contours[0].segments.size() == 3);
    CHECK(std::holds_alternative<LineSegment>(s.contours[0].segments[0]));
    const auto& arc = std::get<ArcSegment>(s.contours[0].segments[1]);
    CHECK(arc.radius == doctest::Approx(0.010));
    CHECK(arc.center.x == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(arc.start_angle > arc.end_angle);  // over the top: clockwise, a convex bump
    const auto& quad = std::get<QuadSegment>(s.contours[0].segments[2]);
    CHECK(quad.p1.x == doctest::Approx(0.020));
    CHECK(quad.p1.y == doctest::Approx(-0.010));
    CHECK(quad.p2.x == doctest::Approx(0.030));
}

TEST_CASE("generators from the menu replace the contours, keep the force settings, and undo") {
    TempDir dir;
    const std::string saved = dir.file("block.json");
    const std::string script = dir.file("gen.txt");
    write_text(script,
               "set ke 800\n"
               "generate block\nexpect valid 1\nexpect ke 800\n"
               "save " + saved + "\n"
               "generate arc\nexpect valid 1\n"
               "undo\nundo\nexpect contours 0\nexpect ke 800\n"
               "open " + saved + "\nexpect valid 1\nexpect dirty 0\nquit\n");
    setenv("TMPDIR", dir.path().c_str(), 1);
    const auto p = run_under_xvfb({"edit", "--script", script, "--software", "--validation", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    const Scene s = load_scene_file(saved);
    const Scene block = generate_block(0.06);
    CHECK(segment_count_of(s) == segment_count_of(block));
    CHECK(s.force.stiffness == 800.0);
}
