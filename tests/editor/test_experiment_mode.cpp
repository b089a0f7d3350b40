// test_experiment_mode.cpp — live trials in the real editor under xvfb-run (issue 16 part 3):
// answers by `answer`, by the keys 1..9 and refused ones, pause and resume, the results written
// row by row, and a second start resuming where the first stopped (the first is killed as a
// crash would: SIGKILL, no exit handler).
#include "process.hpp"
#include "xvfb_editor.hpp"

#include "engine/experiments/base/results_table.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <string>
#include <thread>

using namespace cli_test;
using namespace editor_test;

TEST_CASE("experiment mode: answers become rows at once, a killed session resumes after its last row") {
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature.json").string();
    const std::string results = dir.file("p1.csv");
    const std::vector<std::string> base = {"edit", "--experiment", proto, "--participant", "P1", "--results", results,
                                           "--software", "--timeout", "90", "--script"};
    // Session 1: three answers (one refused, one by key, one across a pause), then killed.
    const std::string s1 = dir.file("s1.txt");
    write_text(s1,
               "expect experiment_total 24\nexpect experiment_done 0\nframes 3\n"
               // The trial's values are the protocol's: an edit is refused.
               "set ke 500\nexpect error 1\n"
               "answer 20\nexpect error 0\nexpect experiment_done 1\n"
               // Never touched (the finger stayed where it was): invalid, presented again.
               "expect experiment_total 25\n"
               "answer 15\nexpect error 1\nexpect experiment_done 1\n"
               "frames 2\nkey 1\nexpect experiment_done 2\n"
               "pause\nexpect experiment_paused 1\nanswer 10\nexpect error 1\nexpect experiment_done 2\n"
               "resume\nframes 2\nanswer 30\nexpect experiment_done 3\nwait 60\nquit\n");
    std::vector<std::string> a1 = base;
    a1.push_back(s1);
    const pid_t xvfb = start_under_xvfb(a1, dir.file("s1.log"));
    bool three = false;
    for (int i = 0; i < 1200 && !three; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        try {
            three = contactlab::experiments::read_results_csv(results).rows.size() == 3;
        } catch (const std::exception&) {
        }
    }
    INFO("session 1: " << read_text(dir.file("s1.log")));
    REQUIRE(three);
    const pid_t editor = find_contactlab(s1);
    REQUIRE(editor > 0);
    REQUIRE(::kill(editor, SIGKILL) == 0);
    int status = 0;
    while (::waitpid(xvfb, &status, 0) < 0 && errno == EINTR) {}
    CHECK_FALSE(contains(read_text(dir.file("s1.log")), "FAILED"));

    const auto t1 = contactlab::experiments::read_results_csv(results);
    CHECK(t1.rows[0][*t1.column("response")] == "20");
    CHECK(t1.rows[1][*t1.column("response")] == "10");  // key 1: the first answer
    CHECK(t1.rows[2][*t1.column("response")] == "30");
    for (int i = 0; i < 3; ++i) {
        // Answered without touching the arc: touched 0 and invalid; the device is named.
        CHECK(t1.rows[i][*t1.column("touched")] == "0");
        CHECK(t1.rows[i][*t1.column("valid")] == "0");
        CHECK(t1.rows[i][*t1.column("device")] == "mouse");
    }
    // The provenance beside the live results: the protocol's hash, the participant, the device.
    const auto meta = nlohmann::json::parse(read_text(results + ".meta.json"));
    CHECK(meta["participants"] == nlohmann::json::array({"P1"}));
    CHECK(meta["device"] == "mouse");
    CHECK(meta["protocol_sha256"].get<std::string>().size() == 64);
    CHECK(meta["finished_utc"].is_null());

    // Session 2: resumes at trial 4 and records one more.
    const std::string s2 = dir.file("s2.txt");
    write_text(s2, "expect experiment_done 3\nframes 3\nanswer 10\nexpect experiment_done 4\nquit\n");
    std::vector<std::string> a2 = base;
    a2.push_back(s2);
    const auto p2 = run_under_xvfb(a2);
    INFO("session 2: " << p2.err);
    CHECK(p2.exit_code == 0);
    CHECK_FALSE(contains(p2.err, "FAILED"));
    CHECK(contains(p2.err, "3 of 27 trials done"));  // the three untouched trials come again
    const auto t2 = contactlab::experiments::read_results_csv(results);
    REQUIRE(t2.rows.size() == 4);
    for (int i = 0; i < 3; ++i) CHECK(t2.rows[i] == t1.rows[i]);  // nothing rewritten
    CHECK(t2.rows[3][*t2.column("trial")] == "4");
}

TEST_CASE("experiment mode: --experiment without --participant, or a bad protocol, exits 2") {
    TempDir dir;
    const auto p = run_under_xvfb({"edit", "--experiment", (source_dir() / "scenes/experiments/003-curvature.json").string(),
                                   "--software", "--frames", "1"});
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "--experiment and --participant go together"));
    write_text(dir.file("bad.json"), "{}");
    const auto q = run_under_xvfb({"edit", "--experiment", dir.file("bad.json"), "--participant", "P1", "--software",
                                   "--frames", "1"});
    CHECK(q.exit_code == 2);
    CHECK(contains(q.err, "bad.json: format: missing"));
}

TEST_CASE("experiment mode: the edge protocol live, two edges a trial and the answer after the second, a staircase's rows") {
    TempDir dir;
    const std::string results = dir.file("edges.csv");
    const std::string script = dir.file("s.txt");
    write_text(script,
               "expect experiment_done 0\nexpect experiment_interval 1\nframes 3\n"
               // Before the second edge the answer is refused and nothing is written.
               "answer first\nexpect error 1\nexpect experiment_done 0\n"
               "key n\nexpect experiment_interval 2\nframes 2\n"
               // Only two edges: a third Next is refused.
               "key n\nexpect error 1\nexpect experiment_interval 2\n"
               "answer second\nexpect error 0\nexpect experiment_done 1\nexpect experiment_interval 1\n"
               "frames 2\nkey n\nframes 2\nkey 1\nexpect experiment_done 2\nquit\n");
    const auto p = run_under_xvfb({"edit", "--experiment", (source_dir() / "scenes/experiments/edge-sharpness.json").string(),
                                   "--participant", "P1", "--results", results, "--software", "--timeout", "90", "--script", script});
    INFO(p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const auto t = contactlab::experiments::read_results_csv(results);
    REQUIRE(t.rows.size() == 2);
    CHECK(t.rows[0][*t.column("response")] == "second");
    CHECK(t.rows[1][*t.column("response")] == "first");
    // The staircase's columns are there, and the first trials are the protocol's practice.
    CHECK(t.rows[0][*t.column("procedure")] == "staircase 1-up-2-down");
    CHECK(t.rows[0][*t.column("warmup")] == "1");
}

TEST_CASE("experiment mode: seed 003 on the simulated wearable, the arc passes under the held finger, again after N") {
    // The device takes the finger from the trial's sweep (LiveSession::sweep): from 2 cm before
    // the 30 cm arc to 2 cm after it at 10 cm/s, left to right for task A, right to left for B.
    TempDir dir;
    const std::string results = dir.file("p1.csv");
    const std::string script = dir.file("s.txt");
    write_text(script,
               "frames 2\nexpect experiment_sweeping 1\nreport start\nwait 2\nreport later\n"
               "answer 20\nexpect error 0\nexpect experiment_done 1\nframes 2\nexpect experiment_sweeping 1\n"
               "key n\nexpect error 0\nexpect experiment_sweeping 1\nquit\n");
    const auto p = run_under_xvfb({"edit", "--device", "sim-wearable", "--experiment",
                                   (source_dir() / "scenes/experiments/003-curvature.json").string(), "--participant", "P1",
                                   "--results", results, "--software", "--timeout", "90", "--script", script});
    INFO(p.err);
    REQUIRE(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));
    const auto t = contactlab::experiments::read_results_csv(results);
    REQUIRE(t.rows.size() == 1);
    CHECK(t.rows[0][*t.column("device")] == "sim-wearable");
    const bool a = t.rows[0][*t.column("condition")] == "A";
    const double x0 = a ? -170.0 : 170.0;  // mm
    const double start = num(report(p.err, "start"), "finger_x_mm"), later = num(report(p.err, "later"), "finger_x_mm");
    CAPTURE(start);
    CAPTURE(later);
    // The finger comes down onto x0 (0.3 s), settles (0.3 s), then passes one way at 0.1 mm a
    // millisecond of servo time (the servo runs in real time): after the first frames it is at
    // x0 or a little past it; two seconds later 140 mm past it (20 mm allows for a servo running
    // at half speed on a loaded machine: 1 s of its time, 0.4 s of it passing).
    CHECK((a ? start - x0 : x0 - start) >= 0.0);
    CHECK((a ? start - x0 : x0 - start) < 100.0);
    CHECK((a ? later - start : start - later) > 20.0);
    // The finger touched the arc's floor and was pressed (the platform shows it).
    CHECK(t.rows[0][*t.column("touched")] == "1");
    CHECK(t.rows[0][*t.column("valid")] == "1");
}
