// test_protocols.cpp — the shipped protocols load; bad protocols are refused naming the file,
// path and why; trial plans are reproducible, balanced and complete; runs do not depend on the
// number of jobs; the simulated participant shows what the seeds' cues predict.
#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/participants/sim_participant.hpp"
#include "engine/experiments/analysis/statistics.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "minimal_protocol.hpp"
#include "process.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <map>
#include <string>

using namespace contactlab::experiments;
using cli_test::TempDir;

namespace {

std::string protocol_path(const char* name) { return (cli_test::source_dir() / "scenes" / "experiments" / name).string(); }

using protocol_test::kMinimal;
using protocol_test::with;

}  // namespace

TEST_CASE("protocols: the four shipped protocols load with the seeds' designs") {
    const Protocol p0 = load_protocol(protocol_path("000-contour-following.json"));
    CHECK(p0.task == Task::contour_following);
    CHECK(p0.stimuli.size() == 7);  // d = 4..10 cm
    CHECK(p0.repetitions == 5);
    const Protocol p2 = load_protocol(protocol_path("002-bump-counting.json"));
    CHECK(p2.trials == 135);
    CHECK(p2.warmup == 10);
    CHECK(p2.answers.size() == 5);
    const Protocol p3 = load_protocol(protocol_path("003-curvature.json"));
    CHECK(p3.conditions.size() == 2);
    CHECK(p3.repetitions == 4);
    CHECK(p3.device == "sim-wearable");  // seed 003's own device; the CLD rig's variant beside it
    CHECK(load_protocol(protocol_path("003-curvature-cld.json")).device == "sim-cld");
    const Protocol p4 = load_protocol(protocol_path("004-surface-orientation.json"));
    CHECK(p4.conditions.size() == 9);  // (e, k) pairs
    CHECK(p4.repetitions == 10);
}

TEST_CASE("protocols: a bad protocol names the file, the JSON path and why") {
    CHECK_NOTHROW(parse_protocol(kMinimal, "p.json"));
    CHECK_THROWS_WITH_AS(parse_protocol(with("\"name\": \"x\"", "\"name\": \"x\", \"colour\": 1"), "p.json"),
                         "p.json: colour: unknown key", ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with("[0.01, 0.02]", "[0.01, 2]"), "p.json"),
                         "p.json: stimuli[1]: must lie in [0.001, 0.1] m (the arc's height), got 2", ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with("\"motion\": \"A\"", "\"motion\": \"C\""), "p.json"),
                         "p.json: conditions[0].motion: expected \"A\" or \"B\" (seed 003's tasks)", ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with("\"task\": \"curvature\"", "\"task\": \"juggling\""), "p.json"),
                         "p.json: task: unknown task \"juggling\" (contour-following, bump-counting, curvature, surface-orientation, edge-sharpness)",
                         ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with("\"stimuli\"", "\"warmup\": 2, \"stimuli\""), "p.json"),
                         "p.json: warmup: leaves no trial to analyse (2 per condition)", ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with("\"name\": \"A\"", "\"name\": \"A,B\""), "p.json"),
                         "p.json: conditions[0].name: must be non-empty, without commas, quotes or line breaks (it is a CSV field)",
                         ExperimentError);
    CHECK_THROWS_AS(parse_protocol("{", "p.json"), ExperimentError);
    CHECK_THROWS_AS(load_protocol("/nonexistent/p.json"), ExperimentError);
}

TEST_CASE("protocols: trial plans are reproducible, balanced across participants and complete") {
    const Protocol p0 = load_protocol(protocol_path("000-contour-following.json"));
    const auto a = plan_trials(p0, 7, 1), b = plan_trials(p0, 7, 1), c = plan_trials(p0, 8, 1), second = plan_trials(p0, 7, 2);
    REQUIRE(a.size() == 2);
    bool same = true, differs = false;
    for (std::size_t k = 0; k < a.size(); ++k)
        for (std::size_t i = 0; i < a[k].size(); ++i) {
            same &= a[k][i].stimulus == b[k][i].stimulus && a[k][i].seed == b[k][i].seed;
            differs |= a[k][i].stimulus != c[k][i].stimulus;
        }
    CHECK(same);
    CHECK(differs);
    CHECK(a[0][0].condition == second[1][0].condition);  // the second participant has the other order
    CHECK(a[0][0].condition != second[0][0].condition);
    for (const auto& block : a) {
        CHECK(block.size() == 35);
        std::map<double, int> count;
        for (const PlannedTrial& t : block) ++count[t.stimulus];
        for (const auto& [d, n] : count) CHECK(n == 5);  // each d five times
    }
    const Protocol p2 = load_protocol(protocol_path("002-bump-counting.json"));
    for (const auto& block : plan_trials(p2, 1, 1)) {
        CHECK(block.size() == 135);
        int warm = 0;
        for (const PlannedTrial& t : block) warm += t.warmup;
        CHECK(warm == 10);
        CHECK(block[9].warmup);
        CHECK_FALSE(block[10].warmup);
    }
}

TEST_CASE("protocols: the results file does not depend on the number of jobs") {
    const Protocol p = load_protocol(protocol_path("003-curvature-cld.json"));
    TempDir dir;
    RunOptions o;
    o.participants = {1, 2, 3};
    o.seed = 5;
    o.traces = false;
    o.output = dir.file("one.csv");
    o.jobs = 1;
    const RunSummary s1 = run_experiment(p, o);
    o.output = dir.file("three.csv");
    o.jobs = 3;
    run_experiment(p, o);
    CHECK(s1.rows == 3 * 24);
    CHECK(cli_test::read_text(dir.file("one.csv")) == cli_test::read_text(dir.file("three.csv")));
    const ResultsTable t = read_results_csv(dir.file("one.csv"));
    CHECK(t.columns == results_columns(p));
}

TEST_CASE("simulated participant: at one hand speed, contact location shows the block's edge in time and force alone does not (seed 000)") {
    // Where the edge is noticed: the element moves 1:1 with the finger once the centre passes the
    // edge (1.5 mm threshold); the force turns by asin(x / R) (15 deg at x = R sin 15 deg = 6.7 mm).
    // Then 0.1 s at 5 cm/s (5 mm) before the finger tips; the pad leaves the top when its centre is
    // more than R sin(L / 2R) = 9.8 mm past the edge. So force alone fails nearly always, with
    // contact location nearly never. The person here keeps the protocol's speed (stop_time_s 0)
    // and neither lapses nor varies their reaction time.
    Protocol p = load_protocol(protocol_path("000-contour-following.json"));
    p.hand_model = HandModel::scripted;  // its path keeps the speed exactly
    p.repetitions = 2;
    p.participant.stop_time_s = 0.0;
    p.participant.lapse_rate_hz = 0.0;
    p.participant.reaction_time_sd_s = 0.0;
    TempDir dir;
    RunOptions o;
    o.participants = {1};
    o.traces = false;
    o.output = dir.file("r.csv");
    run_experiment(p, o);
    const auto j = analyze_results(read_results_csv(o.output));
    CHECK(j["conditions"]["force"]["failure_proportion"].get<double>() >= 0.8);
    CHECK(j["conditions"]["force+cld"]["failure_proportion"].get<double>() <= 0.2);
    // A successful trial takes the path's time from the start line to the finish: at least d plus
    // the 6 cm descent at 5 cm/s.
    CHECK(j["conditions"]["force+cld"]["time_s"]["mean"].get<double>() > (0.04 + 0.06) / 0.05);
}

namespace {

// Seed 000 as run by a person without noise: thresholds exact, no lapses, one reaction time.
// The scripted hand's person (the shipped protocol's hand moves by feel: test_feel_hand.cpp):
// the speeds and times below are its path's.
Protocol noiseless_block_protocol() {
    Protocol p = load_protocol(protocol_path("000-contour-following.json"));
    p.hand_model = HandModel::scripted;
    p.repetitions = 1;
    p.participant.force_angle_noise_deg = 0.0;
    p.participant.location_noise_mm = 0.0;
    p.participant.reaction_time_sd_s = 0.0;
    p.participant.lapse_rate_hz = 0.0;
    p.participant.stop_time_s = 0.22;
    return p;
}

ResultsTable run_one(const Protocol& p, const TempDir& dir, const char* name) {
    RunOptions o;
    o.participants = {1};
    o.traces = false;
    o.output = dir.file(name);
    run_experiment(p, o);
    return read_results_csv(o.output);
}

}  // namespace

TEST_CASE("simulated participant: without contact location the person slides slower, by the pad each cue leaves, and stops in time (seed 000)") {
    // The person moves along the top no faster than lets them stop within the pad after their
    // first cue: v = (L / 2 - cue) / stop_time, the cue R sin 15 deg = 6.73 mm past the edge with
    // force alone, 1.5 mm with contact location: v = 14.9 and 38.6 mm/s. Noticing at the cue, they
    // tip after 0.1 s, overshoot = cue + v 0.1 s = 8.2 and 5.4 mm, inside the 9.8 mm the pad
    // reaches: no trial fails. Each trial's time from the start line: (d + overshoot) / v along the
    // top, then round the corner (about 30 mm) and 6 cm down the far face at the free 5 cm/s.
    const Protocol p = noiseless_block_protocol();
    TempDir dir;
    const ResultsTable t = run_one(p, dir, "r.csv");
    const double half_pad = 0.5 * p.pad_length, reaction = p.participant.reaction_time_s;
    const double r = p.finger_radius - p.hand_press;
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        const auto& row = t.rows[i];
        const bool cld = row[*t.column("condition")] == "force+cld";
        const double cue = cld ? 1.5e-3 : p.finger_radius * std::sin(15.0 * contactlab::kPi / 180.0);
        const double v = (half_pad - cue) / p.participant.stop_time_s;
        const double overshoot = cue + v * reaction;
        const double d = std::stod(row[*t.column("stimulus")]);
        // The corner: the centre swings about the edge from `overshoot` past it at height r to
        // beside it, its radius going from hypot(overshoot, r) to r (drivers/tasks.cpp).
        const double corner = 0.5 * (std::hypot(overshoot, r) + r) * std::atan2(r, overshoot);  // m
        const double expected = (d + overshoot) / v + (corner + 0.06) / p.hand_speed;
        CAPTURE(row[*t.column("condition")]);
        CAPTURE(d);
        CHECK(row[*t.column("failed")] == "0");
        // No break between the start and the finish line: in contact all the timed window.
        CHECK(std::stod(row[*t.column("contact_fraction")]) == 1.0);
        // The cue reaches its threshold up to 1 mm from the nominal x (the finger lags the hand
        // through the grip and the spring), which moves the corner's start by as much.
        CHECK(std::abs(std::stod(row[*t.column("time_s")]) - expected) < 1e-3 / v + 1e-3 / p.hand_speed + 0.01);
    }
}

TEST_CASE("simulated participant: a lapse when the edge comes lets the pad run off the top (seed 000)") {
    // With contact location the noiseless person stops in time (above). Lapsing nearly all the
    // time (10 lapses a second of 0.3 s each: a moment is outside every lapse with probability
    // exp(-3) = 5 %), the element's move goes unnoticed until a lapse ends, up to 0.3 s at
    // 38.6 mm/s = 11.6 mm later, and most trials lose contact.
    Protocol p = noiseless_block_protocol();
    p.conditions.erase(p.conditions.begin());  // force+cld only
    TempDir dir;
    const auto failures = [&](const ResultsTable& t) {
        int n = 0;
        for (const auto& row : t.rows) n += row[*t.column("failed")] == "1";
        return n;
    };
    CHECK(failures(run_one(p, dir, "attentive.csv")) == 0);
    p.participant.lapse_rate_hz = 10.0;
    p.participant.lapse_duration_s = 0.3;
    const ResultsTable lapsing = run_one(p, dir, "lapsing.csv");
    CHECK(failures(lapsing) * 2 >= static_cast<int>(lapsing.rows.size()));
}

TEST_CASE("simulated participant: a person lapsing nearly all the time counts no bumps (seed 002)") {
    // A swing that completes during a lapse is not counted (sim_participant.hpp). Lapsing 10 times
    // a second for 0.3 s each, a moment is outside every lapse with probability exp(-3) = 5 %, so a
    // trial with n swings is answered 0 with probability 0.95^n: at least 0.74 for the up to 6
    // swings (4 bumps and the base's turns) a trial has, 14.7 of 20 trials expected at the least.
    // Attentive, the same person counts at least one bump in most trials (4 in 5 stimuli have one).
    Protocol p = load_protocol(protocol_path("002-bump-counting.json"));
    p.trials = 20;
    p.warmup = 0;
    p.conditions.resize(1);  // F
    TempDir dir;
    const auto zeros = [](const ResultsTable& t) {
        int n = 0;
        for (const auto& row : t.rows) n += row[*t.column("response")] == "0";
        return n;
    };
    p.participant.lapse_rate_hz = 0.0;
    const ResultsTable attentive = run_one(p, dir, "attentive.csv");
    p.participant.lapse_rate_hz = 10.0;
    p.participant.lapse_duration_s = 0.3;
    const ResultsTable lapsing = run_one(p, dir, "lapsing.csv");
    REQUIRE(attentive.rows.size() == 20);
    REQUIRE(lapsing.rows.size() == 20);
    CHECK(zeros(attentive) <= 10);
    CHECK(zeros(lapsing) >= 14);
}

TEST_CASE("simulated participant: on a flat base, without noise or lapses, every bump is counted once (seed 002)") {
    // The person counts a bump where the finger's path rises and turns over a top, and takes the
    // force's and the contact element's swings within a pad length of it as the same bump
    // (sim_participant.hpp). On a flat base nothing else rises: with every threshold at its mean
    // and no lapses the answer is the number of bumps, whether one or four, small or large. The
    // counters that read only the swings got 36 % / 31 % here: a small bump turns the force by
    // less than the threshold, and the element swings both ways over each bump. Bumps closer
    // than a pad length (they may be 15 mm apart) can still read as one: 95 % is asked, not all.
    Protocol p = load_protocol(protocol_path("002-bump-counting.json"));
    p.hand_model = HandModel::scripted;  // its path at the finger's resting height: no motor noise either
    p.base_span = 0.0;
    p.trials = 30;
    p.warmup = 0;
    p.participant.force_angle_noise_deg = 0.0;
    p.participant.location_noise_mm = 0.0;
    p.participant.path_noise_mm = 0.0;
    p.participant.lapse_rate_hz = 0.0;
    TempDir dir;
    const ResultsTable t = run_one(p, dir, "flat.csv");
    std::map<std::string, std::pair<int, int>> by_condition;  // correct, trials
    for (const auto& row : t.rows) {
        auto& cell = by_condition[row[*t.column("condition")]];
        cell.first += row[*t.column("correct")] == "1";
        cell.second += 1;
    }
    REQUIRE(by_condition.size() == 2);
    for (const auto& [condition, cell] : by_condition) {
        CAPTURE(condition);
        CAPTURE(cell.first);
        REQUIRE(cell.second == 30);
        CHECK(cell.first >= 29);  // 95 % of 30, rounded up
    }
}

TEST_CASE("protocols: seed 002 on the text's 20 cm base is the shipped protocol with only the base's span changed") {
    // The seed's text says the base spans 20 cm; the shipped protocol reads it as 20 mm, a
    // "slowly-varying base shape" under the bumps (docs/experiments.md says why), and
    // 002-bump-counting-20cm.json keeps the text's figure.
    const Protocol a = load_protocol(protocol_path("002-bump-counting.json"));
    const Protocol b = load_protocol(protocol_path("002-bump-counting-20cm.json"));
    CHECK(a.base_span == 0.02);
    CHECK(b.base_span == 0.20);
    CHECK(b.trials == a.trials);
    CHECK(b.warmup == a.warmup);
    CHECK(b.conditions.size() == a.conditions.size());
    CHECK(b.small_bump == a.small_bump);
    CHECK(b.large_bump == a.large_bump);
    CHECK(b.traced_length == a.traced_length);
    CHECK(b.hand_speed == a.hand_speed);
    CHECK(b.stiffness == a.stiffness);
    CHECK(b.finger_radius == a.finger_radius);
}

TEST_CASE("protocols: seed 002's base shape spans bumps.base_span, 0 a flat line, out of range refused") {
    // The base shape is scaled to span base_span vertically over the traced length (haptics/
    // stimuli.hpp): with no bumps the contour's points span exactly that, 0 leaves it flat.
    Protocol p = load_protocol(protocol_path("002-bump-counting.json"));
    CHECK(p.base_span == 0.02);
    PlannedTrial t;
    t.stimulus = 0;  // no bumps
    t.seed = 7;
    for (const double span : {0.20, 0.05, 0.02, 0.0}) {
        p.base_span = span;
        const Stimulus st = make_stimulus(p, p.conditions[0], t);
        double lo = 1e9, hi = -1e9;
        for (const auto& seg : st.scene.contours.at(0).segments)
            for (const contactlab::Vec2 q : {contactlab::segment_start(seg), contactlab::segment_end(seg)}) {
                lo = std::min(lo, q.y);
                hi = std::max(hi, q.y);
            }
        CAPTURE(span);
        // The segments' ends lie on the base within a millimetre of its samples (every 2 mm), so
        // they span it to within a few per cent (a turn's top is flat to second order).
        CHECK(std::abs((hi - lo) - span) <= 0.05 * span + 1e-12);
    }
    std::string text = R"({"format": "contactlab experiment protocol", "version": 1, "name": "x", "seed": "002",
      "task": "bump-counting", "conditions": [{"name": "F"}], "stimuli": [0, 1], "answers": ["0", "1"],
      "bumps": {"base_span": 2}})";
    CHECK_THROWS_WITH_AS(parse_protocol(text, "p.json"), doctest::Contains("bumps.base_span"), std::runtime_error);
}

TEST_CASE("protocols: curves may be flattened, an explicit approximation carried into every stimulus") {
    // Exact by default; "curves": {"mode": "flatten", "tolerance": T} renders seed 002's Beziers as
    // chords within T (m), the scene format's own option (scenes/README.md).
    const Protocol exact = load_protocol(protocol_path("002-bump-counting.json"));
    CHECK(exact.curves.mode == contactlab::CurveMode::exact);
    std::string text = cli_test::read_text(protocol_path("002-bump-counting.json"));
    const std::string key = "\"finger\":";
    const auto at = text.find(key);
    REQUIRE(at != std::string::npos);
    auto with_curves = [&](const std::string& curves) {
        std::string t = text;
        return t.insert(at, "\"curves\": " + curves + ", ");
    };
    const Protocol flat = parse_protocol(with_curves(R"({"mode": "flatten", "tolerance": 1e-5})"), "p.json");
    CHECK(flat.curves.mode == contactlab::CurveMode::flatten);
    CHECK(flat.curves.tolerance == 1e-5);
    PlannedTrial t;
    t.stimulus = 3;
    t.seed = 9;
    const Stimulus st = make_stimulus(flat, flat.conditions[0], t);
    CHECK(st.scene.curves.mode == contactlab::CurveMode::flatten);
    CHECK(st.scene.curves.tolerance == 1e-5);
    CHECK(make_stimulus(exact, exact.conditions[0], t).scene.curves.mode == contactlab::CurveMode::exact);
    CHECK_THROWS_WITH_AS(parse_protocol(with_curves(R"({"mode": "flatten", "tolerance": 0.5})"), "p.json"),
                         doctest::Contains("p.json: curves.tolerance: must lie in [1e-09, 0.01] m, got 0.5"), ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with_curves(R"({"mode": "chords"})"), "p.json"),
                         "p.json: curves.mode: unknown curve mode \"chords\" (expected \"exact\" or \"flatten\")", ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with_curves(R"({"tolerance": 1e-5})"), "p.json"), "p.json: curves.mode: missing",
                         ExperimentError);
}

TEST_CASE("simulated participant: seed 002 with curves flattened to 10 um answers as with exact curves, nearly always") {
    // Chords within 10 um of the curve move the finger's path by about that much, against a rise
    // threshold of 0.7 mm (sd 0.2): only a bump whose rise falls within micrometres of the trial's
    // threshold can be counted differently. Over 2,700 trials (10 participants) 6 answers differed
    // (0.2 %); here 40 trials must agree in at least 36, and none may be invalid.
    // The scripted hand: its path is the same in both runs, so only the rendering differs. (The
    // feel hand's closed loop turns a chord's micrometres into another path: docs/experiments.md
    // gives its figures.)
    Protocol exact = load_protocol(protocol_path("002-bump-counting.json"));
    exact.hand_model = HandModel::scripted;
    exact.trials = 20;
    exact.warmup = 0;
    Protocol flat = exact;
    flat.curves.mode = contactlab::CurveMode::flatten;
    flat.curves.tolerance = 1e-5;
    TempDir dir;
    const ResultsTable a = run_one(exact, dir, "exact.csv");
    const ResultsTable b = run_one(flat, dir, "flat.csv");
    REQUIRE(a.rows.size() == 40);
    REQUIRE(b.rows.size() == 40);
    int same = 0, valid = 0;
    for (std::size_t i = 0; i < a.rows.size(); ++i) {
        same += a.rows[i][*a.column("response")] == b.rows[i][*b.column("response")];
        valid += b.rows[i][*b.column("valid")] == "1";
    }
    CHECK(same >= 36);
    CHECK(valid == 40);
}

TEST_CASE("simulated participant: seed 004's field is felt when eccentric and not when e = 1") {
    Protocol p = load_protocol(protocol_path("004-surface-orientation.json"));
    TempDir dir;
    RunOptions o;
    o.participants = {1, 2};
    o.traces = false;
    o.output = dir.file("r.csv");
    run_experiment(p, o);
    // Pooled over k: e = 0.40 against e = 1.00 (120 trials each).
    const ResultsTable t = read_results_csv(o.output);
    std::map<std::string, std::pair<std::vector<std::string>, std::vector<std::string>>> by_e;
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        auto& cell = by_e[t.rows[i][*t.column("e")]];
        cell.first.push_back(t.rows[i][*t.column("stimulus")]);
        cell.second.push_back(t.rows[i][*t.column("response")]);
    }
    const double phi_eccentric = cramers_phi(make_confusion(by_e["0.4"].first, by_e["0.4"].second));
    const double phi_round = cramers_phi(make_confusion(by_e["1"].first, by_e["1"].second));
    CAPTURE(phi_eccentric);
    CAPTURE(phi_round);
    CHECK(phi_eccentric > 0.5);
    // e = 1 is the spring: nothing to feel, answers at chance. Under independence n phi^2 is
    // chi-square with 1 df: phi < 0.24 with 99 % probability at n = 120.
    CHECK(phi_round < 0.24);
}

TEST_CASE("passivity: every shipped protocol runs two simulated participants without an invalid trial") {
    // The passivity observer once charged the loop with the spring energy the hand's turn of the
    // finger puts in (haptics/energy_balance.hpp, `turn`): 14 % of seed 002's trials faulted at the
    // seed's 5 cm/s, 41 % at 10 cm/s, on the text's 20 cm base, whose steep flanks turn the finger
    // most. Seed 002 with 40 trials per condition (of 135), on that base at both speeds and on the
    // shipped 20 mm base; the others as shipped, 000 with 2 repetitions (of 5).
    struct Case {
        const char* file;
        double speed;  // m/s; 0: the protocol's
    };
    for (const Case c : {Case{"002-bump-counting-20cm.json", 0.0}, Case{"002-bump-counting-20cm.json", 0.10}, Case{"002-bump-counting.json", 0.0},
                         Case{"000-contour-following.json", 0.0}, Case{"003-curvature-cld.json", 0.0},
                         Case{"004-surface-orientation.json", 0.0}}) {
        Protocol p = load_protocol(protocol_path(c.file));
        if (p.task == Task::bump_counting) p.trials = 40;
        if (p.task == Task::contour_following) p.repetitions = 2;
        if (c.speed > 0.0) p.hand_speed = c.speed;
        TempDir dir;
        RunOptions o;
        o.participants = {1, 2};
        o.traces = false;
        o.output = dir.file("r.csv");
        const RunSummary s = run_experiment(p, o);
        CAPTURE(std::string(c.file));
        CAPTURE(p.hand_speed);
        CHECK(s.rows > 0);
        CHECK(s.invalid == 0);
    }
}

TEST_CASE("protocols: answers are checked against what each task can answer and how it grades") {
    auto proto = [](const char* task, const char* stimuli, const char* answers, const char* extra = "") {
        return std::string(R"({"format": "contactlab experiment protocol", "version": 1, "name": "x", "seed": "0", "task": ")") + task +
               R"(", "conditions": [{"name": "c")" + extra + R"(}], "stimuli": )" + stimuli + R"(, "answers": )" + answers + "}";
    };
    const char* field = R"(, "eccentricity": 0.4, "total_stiffness": 1000)";
    CHECK_NOTHROW(parse_protocol(proto("surface-orientation", "[45, 135]", R"(["A", "B"])", field), "p.json"));
    // Seed 004: two distinct templates; the axes at 0, 90 and 180 deg are tilted neither way.
    CHECK_THROWS_WITH_AS(parse_protocol(proto("surface-orientation", "[45, 135]", R"(["A", "A"])", field), "p.json"),
                         "p.json: answers[1]: \"A\" appears twice (every answer must be told apart)", ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(proto("surface-orientation", "[45, 135]", R"(["A", "B", "C"])", field), "p.json"),
                         "p.json: answers: two answers: template A (0 < alpha < 90 deg), then B (90 < alpha < 180 deg)",
                         ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(proto("surface-orientation", "[45, 90]", R"(["A", "B"])", field), "p.json"),
                         doctest::Contains("p.json: stimuli[1]: the compliant axis at 0, 90 or 180 deg is tilted neither way"),
                         ExperimentError);
    CHECK(orientation_template(89.999) == 0);
    CHECK(orientation_template(90.001) == 1);
    // Seed 002: the counts 0..N in order, N from the largest stimulus to 4.
    CHECK_NOTHROW(parse_protocol(proto("bump-counting", "[0, 1, 2]", R"(["0", "1", "2"])"), "p.json"));
    CHECK_THROWS_WITH_AS(parse_protocol(proto("bump-counting", "[0, 1, 2]", R"(["0", "1", "3"])"), "p.json"),
                         "p.json: answers[2]: expected \"2\" (bump counting answers are the counts 0 .. N in order), got \"3\"",
                         ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(proto("bump-counting", "[0, 4]", R"(["0", "1", "2"])"), "p.json"),
                         "p.json: answers: bump counting answers are the counts \"0\" .. \"N\", N from the largest stimulus (4) to 4",
                         ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(proto("bump-counting", "[0, 1]", R"(["zero", "one"])"), "p.json"),
                         doctest::Contains("p.json: answers[0]: expected \"0\""), ExperimentError);
    // Seed 003: the heights in mm, each once.
    CHECK_THROWS_WITH_AS(parse_protocol(proto("curvature", "[0.01, 0.02]", R"(["10", "25"])", R"(, "motion": "A")"), "p.json"),
                         "p.json: answers: curvature answers are the stimuli's heights in mm: \"10\", \"20\"", ExperimentError);
    // Every shipped protocol passes.
    for (const char* f : {"000-contour-following.json", "002-bump-counting.json", "002-bump-counting-20cm.json", "003-curvature.json",
                          "003-curvature-cld.json", "004-surface-orientation.json", "edge-sharpness.json"})
        CHECK_NOTHROW(load_protocol(protocol_path(f)));
}
