// test_live_session.cpp — live trials with a person (the editor's experiment mode, without the
// editor): rows written one by one, resuming after a crash without repeating or losing a trial,
// invalid trials presented again at the end of their block, answers outside the set refused.
#include "engine/experiments/runs/live_session.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "process.hpp"

#include <doctest/doctest.h>

#include <set>
#include <string>

using namespace contactlab::experiments;
using cli_test::TempDir;

namespace {
// An answer as the editor gives it (touched and device left to their defaults).
LiveTrialResult result(const char* response, double time_s, int breaks, double peak_force, bool valid) {
    LiveTrialResult r;
    r.response = response;
    r.time_s = time_s;
    r.contact_breaks = breaks;
    r.peak_force = peak_force;
    r.valid = valid;
    return r;
}

Protocol curvature() {
    return load_protocol((cli_test::source_dir() / "scenes/experiments/003-curvature.json").string());
}
}  // namespace

TEST_CASE("live session: each answer is one row on disk, and a restart resumes after the last") {
    TempDir dir;
    const std::string out = dir.file("p07.csv");
    std::set<std::pair<std::string, std::string>> presented;  // (condition, trial)
    {
        LiveSession s(curvature(), "P07", 3, out);
        CHECK(s.total() == 24);
        for (int i = 0; i < 5; ++i) {
            presented.insert({s.condition().name, std::to_string(s.trial().trial)});
            CHECK_FALSE(s.scene().contours.empty());  // the arc to be felt
            s.answer(result("20", 3.0, 0, 1.0, true));
            CHECK(read_results_csv(out).rows.size() == static_cast<std::size_t>(i + 1));
        }
        // The process dies here: nothing after the fifth row.
    }
    LiveSession again(curvature(), "P07", 3, out);
    CHECK(again.resumed() == 5);
    CHECK(again.done() == 5);
    while (!again.finished()) {
        CHECK(presented.insert({again.condition().name, std::to_string(again.trial().trial)}).second);  // never twice
        again.answer(result("10", 2.0, 0, 1.0, true));
    }
    const ResultsTable t = read_results_csv(out);
    CHECK(t.rows.size() == 24);
    CHECK(presented.size() == 24);
    // Another participant in the same file starts from the beginning of its own order.
    LiveSession other(curvature(), "P08", 3, out);
    CHECK(other.done() == 0);
}

TEST_CASE("live session: an invalid trial comes back at the end of its block, a bad answer is refused") {
    TempDir dir;
    const std::string out = dir.file("r.csv");
    LiveSession s(curvature(), "P01", 1, out);
    const std::string first_condition = s.condition().name;
    const int first_trial = s.trial().trial;
    const double stimulus = s.trial().stimulus;
    CHECK_THROWS_AS(s.answer(result("15", 1.0, 0, 1.0, true)), ExperimentError);  // not 10, 20 or 30
    CHECK(s.done() == 0);
    s.answer(result("10", 1.0, 0, 1.0, false));  // the servo faulted
    CHECK(s.total() == 25);
    // The repeat is the 13th trial of the first block, the same stimulus.
    while (s.condition().name == first_condition && s.trial().trial != 13) s.answer(result("10", 1.0, 0, 1.0, true));
    CHECK(s.condition().name == first_condition);
    CHECK(s.trial().stimulus == stimulus);
    CHECK(first_trial == 1);
    const ResultsTable t = read_results_csv(out);
    CHECK(t.rows[0][*t.column("valid")] == "0");
    // Resuming rebuilds the repeat from the file's invalid row.
    LiveSession resumed(curvature(), "P01", 1, out);
    CHECK(resumed.total() == 25);
    CHECK(resumed.trial().trial == 13);
}

TEST_CASE("live session: rows say the device and whether the finger touched, an untouched answer is invalid and comes again") {
    TempDir dir;
    const std::string out = dir.file("r.csv");
    LiveSession s(curvature(), "P02", 1, out);
    CHECK(s.total() == 24);
    const double first_stimulus = s.trial().stimulus;
    s.answer(result("10", 1.0, 0, 0.0, true));  // no force at all: not touched
    LiveTrialResult r = result("10", 1.0, 0, 0.8, true);
    r.device = "mouse";
    s.answer(r);  // a force: touched
    r.touched = false;
    s.answer(r);  // the editor says it did not touch
    const ResultsTable t = read_results_csv(out);
    const std::size_t touched = *t.column("touched"), device = *t.column("device"), unit = *t.column("stimulus_unit");
    CHECK(t.rows[0][touched] == "0");
    CHECK(t.rows[1][touched] == "1");
    CHECK(t.rows[2][touched] == "0");
    CHECK(t.rows[0][device].empty());
    CHECK(t.rows[1][device] == "mouse");
    CHECK(t.rows[0][unit] == "mm");
    // An answer about a stimulus never touched says nothing of the display: invalid (left out of
    // the analysis) and presented again at the end of its block, like a faulted trial.
    const std::size_t valid = *t.column("valid");
    CHECK(t.rows[0][valid] == "0");
    CHECK(t.rows[1][valid] == "1");
    CHECK(t.rows[2][valid] == "0");
    CHECK(s.total() == 26);
    while (s.trial().trial != 13) s.answer(result("10", 1.0, 0, 1.0, true));
    CHECK(s.trial().stimulus == first_stimulus);
}
