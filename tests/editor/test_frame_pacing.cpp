// test_frame_pacing.cpp — issue 18: the editor draws only when something changed, and keeps the
// scene layer as a picture. The redraw rule as a unit (counts, no clocks), then the real editor
// under xvfb-run: an idle editor draws next to nothing (counted, not timed), still redraws while
// the force ramps in, keeps recording every tick while idle; and the kept scene layer is drawn
// again after a scene edit and a view change, with the pixels of a fresh draw each time.
#include "engine/editor/redraw_policy.hpp"

#include "csv.hpp"
#include "xvfb_editor.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using namespace contactlab;
using namespace contactlab::editor;
using namespace cli_test;
using namespace editor_test;

namespace {

struct Wake {
    std::uint64_t events = 0, revision = 1, generation = 1;
    ServoSnapshot snap;
    std::string message = "opened";
    RedrawInputs inputs() const {
        RedrawInputs in;
        in.events = events;
        in.doc_revision = revision;
        in.servo_generation = generation;
        in.snapshot = &snap;
        in.message = &message;
        return in;
    }
};

// Frames drawn over `wakes` wakes 10 ms apart from `t0`, nothing changing.
int frames_over(RedrawPolicy& p, const Wake& w, double t0, int wakes) {
    int drawn = 0;
    for (int i = 0; i < wakes; ++i) {
        const double t = t0 + 0.01 * i;
        if (p.should_draw(w.inputs(), t)) {
            p.drawn(w.inputs(), t);
            ++drawn;
        }
    }
    return drawn;
}

}  // namespace

TEST_CASE("redraw policy: nothing changing draws once a refresh period, input draws and settles") {
    RedrawPolicy p;
    Wake w;
    CHECK(p.should_draw(w.inputs(), 0.0));  // the first frame
    p.drawn(w.inputs(), 0.0);
    // The first frame counts as input: kAfterInput more, then only the refresh.
    CHECK(frames_over(p, w, 0.01, 10) == RedrawPolicy::kAfterInput);
    CHECK(frames_over(p, w, 0.2, 70) == 0);        // up to 0.89 s: nothing
    CHECK(frames_over(p, w, 0.9, 300) == 3);       // 0.9..3.9 s: one a second
    // Input: a frame now and kAfterInput after it.
    ++w.events;
    CHECK(frames_over(p, w, 5.0, 20) == 1 + RedrawPolicy::kAfterInput);
}

TEST_CASE("redraw policy: the servo's picture, the document and the message each make a frame") {
    RedrawPolicy p;
    Wake w;
    frames_over(p, w, 0.0, 10);
    REQUIRE_FALSE(p.should_draw(w.inputs(), 0.5));
    SUBCASE("float noise in the servo's state is not a change") {
        w.snap.finger.x += 1e-9;
        w.snap.force.y += 1e-7;
        w.snap.ticks += 100;
        w.snap.t += 0.1;
        CHECK_FALSE(p.should_draw(w.inputs(), 0.5));
    }
    SUBCASE("the finger moving a micrometre is") {
        w.snap.finger.x += 2e-6;
        CHECK(p.should_draw(w.inputs(), 0.5));
    }
    SUBCASE("the force ramping is") {
        w.snap.force.y += 1e-3;
        CHECK(p.should_draw(w.inputs(), 0.5));
    }
    SUBCASE("a servo state change is") {
        w.snap.state = ServoState::engaged;
        CHECK(p.should_draw(w.inputs(), 0.5));
    }
    SUBCASE("a document edit is") {
        ++w.revision;
        CHECK(p.should_draw(w.inputs(), 0.5));
    }
    SUBCASE("a device or rate switch is") {
        ++w.generation;
        CHECK(p.should_draw(w.inputs(), 0.5));
    }
    SUBCASE("a new message is") {
        w.message = "saved";
        CHECK(p.should_draw(w.inputs(), 0.5));
    }
}

TEST_CASE("idle editor: next to no frames while nothing moves, every tick still recorded") {
    TempDir dir;
    const std::string script = dir.file("idle.txt"), rec = dir.file("idle.csv");
    // Settled first (the servo engaged, the window's first events handled), then 3 s idle
    // recording, then 1.5 s idle while the force ramps in after an emergency stop.
    write_text(script,
               "set snap_mm 1\ntool line\nclick -40 0\nclick 40 0\nrclick 40 0\n"
               "finger 0 40 0\nwait_state engaged 5\n"
               "finger 0 25 0\nwait_contact 3\nwait 0.5\n"
               "record " + rec + "\n"
               "idle 3\n"
               "expect idle_frames 0 5\n"
               "record stop\n"
               "estop on\nwait 0.3\nestop off\n"
               "idle 1.5\n"
               "report ramp\n"
               "expect force 1 0.000001\n"
               "quit\n");
    const auto p = run_validated_script(script, dir.path());
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    // Idle: at most a refresh a second (kRefresh), against ~180 at 60 fps.
    CHECK(contains(p.err, "script idle: "));
    // The ramp (0.2 s of changing force) drew frames during the second idle, then it went quiet:
    // more than the refreshes alone, far fewer than continuous drawing.
    const auto at = p.err.rfind("script idle: ");
    REQUIRE(at != std::string::npos);
    const long ramp_frames = std::strtol(p.err.c_str() + at + 13, nullptr, 10);
    CHECK(ramp_frames > 3);
    CHECK(ramp_frames < 60);
    // The recording ring was drained while idle: no tick dropped, and the file holds every tick
    // the servo ran in those 3 s at 1 kHz (a late tick from a stalled machine is still a tick:
    // how late is the benchmarks' business, not a unit test's).
    const Csv take = parse_csv(read_text(rec));
    CHECK(take.rows.size() > 2800);
    const auto said = p.err.find("script record: recording written to ");
    REQUIRE(said != std::string::npos);
    const std::string line = p.err.substr(said, p.err.find('\n', said) - said);
    INFO("record stop said: " << line);
    CHECK(contains(line, "(" + std::to_string(take.rows.size()) + " ticks, 0 dropped)"));
    // The rows are the ticks in order: time never goes back, and no row repeats one.
    for (std::size_t i = 1; i < take.rows.size(); ++i) {
        INFO("row " << i);
        REQUIRE(take.rows[i][0] > take.rows[i - 1][0]);
    }
}

TEST_CASE("kept scene layer: drawn again after a scene edit and a view change, pixels of a fresh draw") {
    TempDir dir;
    // A copy: the edit below leaves a recovery file beside the scene (never beside scenes/).
    const std::string script = dir.file("layer.txt"), block = dir.file("block.json");
    write_text(block, read_text((source_dir() / "scenes" / "block.json").string()));
    setenv("TMPDIR", dir.path().c_str(), 1);
    write_text(script,
               "frames 3\ncheck_layer\nexpect layer_mismatch 0\nreport start\n"
               "frames 5\nreport still\n"
               "generate arc\nframes 2\ncheck_layer\nexpect layer_mismatch 0\nreport edited\n"
               "finger 250 150\nfit\nframes 2\ncheck_layer\nexpect layer_mismatch 0\nreport viewed\n"
               "undo\nframes 2\ncheck_layer\nexpect layer_mismatch 0\nreport undone\n"
               "quit\n");
    const auto p = run_under_xvfb({"edit", block, "--script", script, "--software",
                                   "--validation", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const double start = num(report(p.err, "start"), "scene_layer_updates");
    CHECK(start >= 1);
    // Frames with nothing changed reuse the picture; an edit and a view change each draw one.
    CHECK(num(report(p.err, "still"), "scene_layer_updates") == start);
    CHECK(num(report(p.err, "edited"), "scene_layer_updates") == start + 1);
    CHECK(num(report(p.err, "viewed"), "scene_layer_updates") == start + 2);
    CHECK(num(report(p.err, "undone"), "scene_layer_updates") == start + 3);
}
