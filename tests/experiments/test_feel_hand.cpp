// test_feel_hand.cpp — the hand that moves by feel (participants/feel_hand.hpp, feel_tasks.hpp)
// and the people it belongs to (person.hpp): its press loop settles on the person's force, it
// slides at the speed it is told, it feels late by the person's delay, and seed 000 by feel
// behaves as its cues predict; people are drawn from the documented population.
#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/participants/feel_hand.hpp"
#include "engine/experiments/participants/person.hpp"
#include "engine/experiments/participants/servo_trial.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "engine/experiments/runs/experiment_run.hpp"
#include "drivers/sim/sim_rig.hpp"
#include "process.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace contactlab;
using namespace contactlab::experiments;
using cli_test::TempDir;

namespace {

std::string protocol_path(const char* name) { return (cli_test::source_dir() / "scenes" / "experiments" / name).string(); }

// A person without motor noise, to check the loop's own behaviour.
Person quiet_person(double delay = 0.12, double force = 0.6) {
    Person p;
    p.delay_s = delay;
    p.press_force_n = force;
    p.force_noise_cv = 0.0;
    p.speed_noise_cv = 0.0;
    return p;
}

// Runs `hand` over `scene` from `start`, told `speed` (m/s) once it has felt contact for 0.3 s.
TrialTrace slide_after_touch(const Scene& scene, const drivers::HandPath& envelope, const drivers::PathSample& start,
                             FeelHand& hand, double speed, double seconds) {
    double felt_since = -1.0;
    const Steer steer = [&](const drivers::TickRecord& r, drivers::PathSample& next) {
        if (hand.felt_contact() && felt_since < 0.0) felt_since = r.t;
        if (felt_since >= 0.0 && r.t - felt_since >= 0.3) hand.set_speed(speed);
        next = hand.step(r);
        return true;
    };
    return run_steered_trial(scene, envelope, start, false, steer, seconds);
}

// The hand over seed 000's rendering of a flat floor (y = 0, 1000 N/m, 1.5 N), starting 1 cm
// above it; `speed` (m/s) set once contact has been felt for 0.3 s; `seconds` of virtual time.
TrialTrace press_floor(const Person& person, double speed, double seconds) {
    Scene scene = drivers::sim::floor_scene(1000.0);
    scene.finger.radius = 0.026;
    scene.finger.length = 0.020;
    scene.force.max_force = 1.5;
    const drivers::PathSample start{0.0, Vec2{-0.05, 0.026 + 0.01}, 0.0};
    const drivers::HandPath envelope(std::vector<drivers::PathSample>{start, {1.0, Vec2{0.05, 0.023}, 0.0}});
    FeelHand hand(person, start, 1e-3, 7);
    hand.set_approach(0.03);
    return slide_after_touch(scene, envelope, start, hand, speed, seconds);
}

// Contacts lost after the first touch: a tick in contact followed by one out of it.
int contact_breaks(const TrialTrace& tr) {
    int n = 0;
    bool touched = false, prev = false;
    for (const auto& r : tr.ticks) {
        if (touched && prev && !r.contact) ++n;
        touched |= r.contact;
        prev = r.contact;
    }
    return n;
}

double mean_force(const TrialTrace& tr, double from, double to) {
    double sum = 0.0;
    int n = 0;
    for (const auto& r : tr.ticks)
        if (r.t >= from && r.t <= to) sum += std::hypot(r.force.x, r.force.y), ++n;
    return n ? sum / n : NAN;
}

}  // namespace

TEST_CASE("feel hand: pressing a floor, the force settles on the person's press force") {
    // An integral force loop with gain 0.4 / (delay x 240 N/m): it settles in a few delays with
    // no overshoot left; after 2 s the force is the target to within the rig's own ripple.
    for (const double target : {0.4, 0.9}) {
        CAPTURE(target);
        const TrialTrace tr = press_floor(quiet_person(0.12, target), 0.0, 3.0);
        REQUIRE_FALSE(tr.faulted);
        CHECK(mean_force(tr, 2.0, 3.0) == doctest::Approx(target).epsilon(0.03));
        CHECK(contact_breaks(tr) == 0);
    }
}

TEST_CASE("feel hand: it reaches later and presses harder on touching the longer its delay") {
    // Reaching down at 30 mm/s, the hand learns of the contact `delay` late and has pushed on by
    // 30 mm/s x delay: through the hand (300 N/m) in series with the floor (1000 N/m), 231 N/m,
    // the force at that moment is 6.9 N/s x delay, the first peak's bulk. Both peaks stay under
    // the 1.5 N limit.
    auto peak = [](double delay) {
        const TrialTrace tr = press_floor(quiet_person(delay, 0.3), 0.0, 1.5);
        double p = 0.0;
        for (const auto& r : tr.ticks) p = std::max(p, std::hypot(r.force.x, r.force.y));
        return p;
    };
    const double fast = peak(0.08), slow = peak(0.14);
    CHECK(slow < 1.5);
    CHECK(slow > fast);
    CHECK(slow - fast == doctest::Approx(6.9 * (0.14 - 0.08)).epsilon(0.5));
}

TEST_CASE("feel hand: sliding along a floor at the speed it is told, in contact throughout") {
    const double v = 0.03;  // m/s
    const TrialTrace tr = press_floor(quiet_person(), v, 3.0);
    // Over the last second: x advances at v (the speed's 0.15 s lag long settled).
    const auto at = [&](double t) {
        const auto it = std::find_if(tr.ticks.begin(), tr.ticks.end(), [&](const auto& r) { return r.t >= t; });
        return it->finger.x;
    };
    CHECK((at(2.9) - at(1.9)) / 1.0 == doctest::Approx(v).epsilon(0.02));
    for (const auto& r : tr.ticks)
        if (r.t > 1.0) REQUIRE(r.contact);
}

TEST_CASE("people: drawn from the documented population, the same person for the same seed") {
    const Person a = draw_person(42), b = draw_person(42), c = draw_person(43);
    CHECK(a.delay_s == b.delay_s);
    CHECK(a.pace == b.pace);
    CHECK(a.pace != c.pace);
    // 4000 people: each mean within 5 standard errors of the population's.
    const int n = 4000;
    double delay = 0.0, log_press = 0.0, log_pace = 0.0, log_pace2 = 0.0;
    double lo = 1.0, hi = 0.0;
    for (int i = 0; i < n; ++i) {
        const Person p = draw_person(static_cast<std::uint64_t>(i) * 7919u + 1u);
        delay += p.delay_s;
        lo = std::min(lo, p.delay_s);
        hi = std::max(hi, p.delay_s);
        log_press += std::log(p.press_force_n);
        log_pace += std::log(p.pace);
        log_pace2 += std::log(p.pace) * std::log(p.pace);
    }
    const PersonPopulation& q = kPopulation;
    CHECK(delay / n == doctest::Approx(q.delay_mean_s).epsilon(5.0 * q.delay_sd_s / std::sqrt(n) / q.delay_mean_s));
    CHECK(lo >= q.delay_min_s);
    CHECK(hi <= q.delay_max_s);
    CHECK(std::exp(log_press / n) == doctest::Approx(q.press_median_n).epsilon(5.0 * q.press_log_sd / std::sqrt(n)));
    const double m = log_pace / n, sd = std::sqrt(log_pace2 / n - m * m);
    CHECK(std::abs(m) < 5.0 * q.pace_log_sd / std::sqrt(n));
    CHECK(sd == doctest::Approx(q.pace_log_sd).epsilon(0.05));
}

TEST_CASE("protocols: hand.model names the hand, scripted or feel, and anything else is refused") {
    // Seeds 000 and 002 ship with the hand that moves by feel; the other tasks' strategies keep
    // the scripted slide or press, and a protocol without hand.model gets the scripted hand.
    for (const char* name : {"000-contour-following.json", "002-bump-counting.json", "002-bump-counting-20cm.json"}) {
        CAPTURE(name);
        CHECK(load_protocol(protocol_path(name)).hand_model == HandModel::feel);
    }
    for (const char* name : {"003-curvature.json", "003-curvature-cld.json", "004-surface-orientation.json", "edge-sharpness.json"}) {
        CAPTURE(name);
        CHECK(load_protocol(protocol_path(name)).hand_model == HandModel::scripted);
    }
    HandModel h = HandModel::scripted;
    CHECK(parse_hand_model("feel", h));
    CHECK(h == HandModel::feel);
    CHECK_FALSE(parse_hand_model("Feel", h));
    CHECK(std::string(to_string(HandModel::feel)) == "feel");
    // Only contour following and bump counting have such a hand: elsewhere "feel" would run the
    // scripted strategy while the meta said feel, so it is refused naming the key.
    CHECK(task_has_feel_hand(Task::contour_following));
    CHECK(task_has_feel_hand(Task::bump_counting));
    for (const Task t : {Task::curvature, Task::surface_orientation, Task::edge_sharpness}) CHECK_FALSE(task_has_feel_hand(t));
    const std::string curvature = R"({"format": "contactlab experiment protocol", "version": 1, "name": "x", "seed": "003",
  "task": "curvature", "conditions": [{"name": "A", "motion": "A"}], "stimuli": [0.01, 0.02], "answers": ["10", "20"],
  "hand": {"model": "feel"}})";
    CHECK_THROWS_WITH_AS(parse_protocol(curvature, "c.json"),
                         doctest::Contains("c.json: hand.model: \"feel\": this is a curvature protocol, whose simulated person has no hand that moves by feel"),
                         ExperimentError);
    std::string scripted = curvature;
    scripted.replace(scripted.find("\"feel\""), 6, "\"scripted\"");
    CHECK(parse_protocol(scripted, "c.json").hand_model == HandModel::scripted);
}

TEST_CASE("simulated participant by feel: seed 000 without noise, the edge is felt in time with contact location, and time rises with d") {
    // A noiseless person (exact thresholds, no lapses, one reaction time): with contact
    // location the element's 1.5 mm move is felt with the pad's reach past the edge still ahead,
    // and the speed leaves the reaction (0.1 s) and one feedback delay (about 0.12 s) of it,
    // shortened by their pace, to tip: at the pace of participant 1 (below 1.3) the hand tips
    // before the pad leaves the top, and no trial fails. Each trial's time from the start line
    // grows with d at the top's speed.
    Protocol p = load_protocol(protocol_path("000-contour-following.json"));
    p.hand_model = HandModel::feel;
    p.repetitions = 1;
    p.conditions.erase(p.conditions.begin());  // force+cld only
    p.participant.force_angle_noise_deg = 0.0;
    p.participant.location_noise_mm = 0.0;
    p.participant.reaction_time_sd_s = 0.0;
    p.participant.lapse_rate_hz = 0.0;
    TempDir dir;
    RunOptions o;
    o.participants = {1};
    o.traces = false;
    o.output = dir.file("r.csv");
    run_experiment(p, o);
    const ResultsTable t = read_results_csv(o.output);
    REQUIRE(t.rows.size() == p.stimuli.size());
    const Person person = draw_person(person_seed(o.seed, 1));
    REQUIRE(person.pace < 1.3);
    std::vector<std::pair<double, double>> times;  // d (m), time (s)
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        CAPTURE(t.rows[i][*t.column("stimulus")]);
        CHECK(t.rows[i][*t.column("failed")] == "0");
        CHECK(std::stod(t.rows[i][*t.column("contact_fraction")]) == 1.0);
        times.emplace_back(std::stod(t.rows[i][*t.column("stimulus")]), std::stod(t.rows[i][*t.column("time_s")]));
    }
    std::sort(times.begin(), times.end());
    // From d = 4 to 10 cm the top adds 6 cm at the person's speed: the pad left past the 1.5 mm
    // cue over (0.1 s + a delay) / pace, the pad being L/2 = 10 mm or, pressing lightly, the
    // sqrt(2 R F* / k) past the edge where the hand's intended point leaves the corner's circle
    // (k = 240 N/m), capped at the hand speed of 50 mm/s.
    const double reach = std::min(0.01, std::sqrt(2.0 * 0.026 * person.press_force_n / 240.0));
    const double v = std::min((reach - 0.0015) * person.pace / (0.1 + person.delay_s), 0.05);
    CHECK(times.back().second - times.front().second == doctest::Approx(0.06 / v).epsilon(0.15));
}

TEST_CASE("simulated participant by feel: seed 000 with force alone, each person slides along the top at the pace their own threshold allows") {
    // People differ in how far the force must turn before they notice it (participant.hand's
    // angle_threshold_sd_deg): each person's speed along the top leaves the pad past *their* cue,
    // R sin(their threshold) past the edge, for their reaction and a delay. Noiseless people (no
    // trial-to-trial threshold noise, no lapses, no pitch drift), force alone: each trial's time
    // grows from d = 4 to 10 cm by 6 cm at that speed, so the person with the higher threshold is
    // the slower, by the ratio of the pad their cues leave.
    Protocol p = load_protocol(protocol_path("000-contour-following.json"));
    p.hand_model = HandModel::feel;
    p.repetitions = 1;
    p.conditions.erase(p.conditions.begin() + 1);  // force alone only
    REQUIRE_FALSE(p.conditions.front().contact_location);
    p.participant.force_angle_noise_deg = 0.0;
    p.participant.reaction_time_sd_s = 0.0;
    p.participant.lapse_rate_hz = 0.0;
    p.participant.hand.angle_drift_rad_sqrt_m = 0.0;
    p.participant.hand.angle_threshold_sd_deg = 3.0;
    TempDir dir;
    RunOptions o;
    o.participants = {1, 2, 3};
    o.traces = false;
    o.output = dir.file("r.csv");
    run_experiment(p, o);
    const ResultsTable t = read_results_csv(o.output);
    REQUIRE(t.rows.size() == 3 * p.stimuli.size());
    std::vector<double> offsets;
    for (int who = 1; who <= 3; ++who) {
        const Person person = draw_person(person_seed(o.seed, who), p.participant.hand);
        CAPTURE(who);
        CAPTURE(person.angle_threshold_offset_deg);
        offsets.push_back(person.angle_threshold_offset_deg);
        double t4 = NAN, t10 = NAN;
        for (const auto& row : t.rows) {
            if (row[*t.column("participant")] != "sim" + std::to_string(who) || row[*t.column("failed")] != "0") continue;
            const double d = std::stod(row[*t.column("stimulus")]);
            if (std::abs(d - 0.04) < 1e-9) t4 = std::stod(row[*t.column("time_s")]);
            if (std::abs(d - 0.10) < 1e-9) t10 = std::stod(row[*t.column("time_s")]);
        }
        REQUIRE(std::isfinite(t4));
        REQUIRE(std::isfinite(t10));
        const double reach = std::min(0.01, std::sqrt(2.0 * 0.026 * person.press_force_n / 240.0));  // m past the edge
        const double cue = 0.026 * std::sin((15.0 + person.angle_threshold_offset_deg) * kPi / 180.0);  // m past the edge
        const double v = std::clamp((reach - cue) * person.pace / (0.1 + person.delay_s), 0.002, 0.05);  // m/s
        CHECK(t10 - t4 == doctest::Approx(0.06 / v).epsilon(0.15));
    }
    // The three people's thresholds differ (else the check above shows nothing of the spread).
    CHECK(*std::max_element(offsets.begin(), offsets.end()) - *std::min_element(offsets.begin(), offsets.end()) > 1.0);
}

TEST_CASE("people: their own force-direction thresholds spread as the population says, the first five draws unchanged") {
    HandPopulation q = kPopulation;
    q.angle_threshold_sd_deg = 0.0;
    const Person none = draw_person(42, q);
    CHECK(none.angle_threshold_offset_deg == 0.0);
    q.angle_threshold_sd_deg = 3.0;
    const Person some = draw_person(42, q);
    // The threshold is drawn after the others: the same person otherwise.
    CHECK(some.delay_s == none.delay_s);
    CHECK(some.pace == none.pace);
    CHECK(some.speed_noise_cv == none.speed_noise_cv);
    const int n = 4000;
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double o = draw_person(static_cast<std::uint64_t>(i) * 7919u + 1u, q).angle_threshold_offset_deg;
        s += o, s2 += o * o;
    }
    const double m = s / n, sd = std::sqrt(s2 / n - m * m);
    CHECK(std::abs(m) < 5.0 * 3.0 / std::sqrt(n));
    CHECK(sd == doctest::Approx(3.0).epsilon(0.05));
}

TEST_CASE("experiment run --hand: feel is recorded in the meta, a bad name exits 2 naming the option") {
    TempDir dir;
    const std::string proto = protocol_path("000-contour-following.json");
    const auto bad = cli_test::run_contactlab({"experiment", "run", proto, "--participant", "sim", "--hand", "fel", "-o", dir.file("b.csv")});
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--hand: expected scripted or feel, got \"fel\"") != std::string::npos);
    const auto p = cli_test::run_contactlab(
        {"experiment", "run", proto, "--participant", "sim", "--hand", "feel", "--no-traces", "--jobs", "1", "-o", dir.file("r.csv")});
    INFO(p.err);
    REQUIRE(p.exit_code == 0);
    const auto meta = nlohmann::json::parse(cli_test::read_text(dir.file("r.csv.meta.json")));
    CHECK(meta["hand"] == "feel");
    const ResultsTable t = read_results_csv(dir.file("r.csv"));
    CHECK(t.rows.size() == 70);
    // The same run again with the scripted hand is another study: refused, not resumed.
    const auto other = cli_test::run_contactlab(
        {"experiment", "run", proto, "--participant", "sim", "--hand", "scripted", "--no-traces", "--jobs", "1", "-o", dir.file("r.csv")});
    CHECK(other.exit_code == 2);
    CHECK(other.err.find("another hand") != std::string::npos);
    // --hand feel on a task without such a hand: refused before anything runs, naming the file.
    const std::string curvature = protocol_path("003-curvature.json");
    const auto none = cli_test::run_contactlab(
        {"experiment", "run", curvature, "--participant", "sim", "--hand", "feel", "--no-traces", "-o", dir.file("c.csv")});
    CHECK(none.exit_code == 2);
    CHECK(none.err.find("--hand feel: " + curvature + " is a curvature protocol, whose simulated person has no hand that moves by feel") !=
          std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir.file("c.csv")));
}

namespace {

// The hand over a floor that rises at 45 deg at x = 0 by 20 mm (seed 002's large bumps rise as
// steeply), sliding at `speed` from x = -3 cm once contact has been felt for 0.3 s, guarded or
// not; `seconds` of virtual time.
TrialTrace climb_ramp(bool guarded, double speed, double seconds) {
    Scene scene;
    Contour c;
    c.segments.push_back(LineSegment{{-1.0, 0.0}, {0.0, 0.0}});
    c.segments.push_back(LineSegment{{0.0, 0.0}, {0.02, 0.02}});
    c.segments.push_back(LineSegment{{0.02, 0.02}, {1.0, 0.02}});
    scene.contours.push_back(c);
    scene.force.stiffness = 1300.0;
    scene.force.max_force = 1.5;
    scene.finger.radius = 0.020;
    scene.finger.length = 0.020;
    const drivers::PathSample start{0.0, Vec2{-0.03, 0.020 + 0.005}, 0.0};
    const drivers::HandPath envelope(std::vector<drivers::PathSample>{start, {1.0, Vec2{0.06, 0.04}, 0.0}});
    FeelHand hand(quiet_person(0.12, 0.6), start, 1e-3, 7);
    hand.set_approach(0.03);
    hand.set_guarded(guarded);
    hand.follow_normal(0.0);
    return slide_after_touch(scene, envelope, start, hand, speed, seconds);
}

}  // namespace

TEST_CASE("feel hand: out of touch it does not advance, and it advances once it touches") {
    // Told to slide at 30 mm/s from the start, 1 cm above the floor: it reaches down (30 mm/s
    // along the last felt normal, straight down) without moving along x until the touch is felt,
    // a delay after it happens; from then on it slides at the speed it was told.
    const double v = 0.03;
    const TrialTrace tr = press_floor(quiet_person(), v, 2.5);
    REQUIRE_FALSE(tr.faulted);
    const auto first = std::find_if(tr.ticks.begin(), tr.ticks.end(), [](const auto& r) { return r.contact; });
    REQUIRE(first != tr.ticks.end());
    // The reach's own sway: the finger lands where it started, to within a tenth of a millimetre.
    CHECK(std::abs(first->finger.x - (-0.05)) < 1e-4);
    // Over the last second: x advances at v.
    const auto at = [&](double t) {
        const auto it = std::find_if(tr.ticks.begin(), tr.ticks.end(), [&](const auto& r) { return r.t >= t; });
        return it->finger.x;
    };
    CHECK((at(2.4) - at(1.4)) / 1.0 == doctest::Approx(v).epsilon(0.03));
}

TEST_CASE("feel hand: a guarded slide holds back against a rising face and climbs it") {
    const TrialTrace free = climb_ramp(false, 0.05, 3.0), guarded = climb_ramp(true, 0.05, 3.0);
    REQUIRE_FALSE(free.faulted);
    REQUIRE_FALSE(guarded.faulted);
    const auto over = [](const TrialTrace& tr, double f) {
        double s = 0.0;
        for (const auto& r : tr.ticks) s += std::hypot(r.force.x, r.force.y) > f ? 1e-3 : 0.0;
        return s;
    };
    // Unguarded, the hand pushes on along the lagging felt tangent until the felt normal has
    // turned, and sits at the display's 1.5 N limit for 0.17 s; guarded, it stops advancing a
    // delay after the force passed twice its 0.6 N target, which takes at least a third of a
    // delay (0.04 s) off the time at the limit (0.11 s), and off the time over twice the target.
    const double sat_free = over(free, 1.45), sat_guarded = over(guarded, 1.45);
    CAPTURE(sat_free);
    CAPTURE(sat_guarded);
    CHECK(sat_free > 0.12);
    CHECK(sat_guarded < sat_free - 0.04);
    CHECK(over(guarded, 1.2) < over(free, 1.2) - 0.04);
    // Both climb: within 3 s the guarded finger's centre is past the face's top (x = 2 cm) and on
    // the upper floor (its centre a radius, 20 mm, above y = 2 cm, less the press's sinking,
    // up to 1.2 mm at the 1.5 N limit and 1300 N/m: 3 % of 4 cm).
    CHECK(guarded.ticks.back().finger.x > 0.02);
    CHECK(guarded.ticks.back().finger.y == doctest::Approx(0.04).epsilon(0.03));
    CHECK(contact_breaks(free) <= 2);
    CHECK(contact_breaks(guarded) <= 2);
}

TEST_CASE("protocols: participant.hand sets the feel hand's population, and a bad key or value is refused naming it") {
    const std::string text = cli_test::read_text(protocol_path("002-bump-counting.json"));
    const auto with_hand = [&](const std::string& hand) {
        std::string t = text;
        t.insert(t.rfind('}'), R"(, "participant": {"hand": )" + hand + "}");
        return t;
    };
    const Protocol p = parse_protocol(with_hand(R"({"slide_speed_mps": 0.07, "pace_log_sd": 0.1})"), "p.json");
    CHECK(p.participant.hand.slide_speed_mps == 0.07);
    CHECK(p.participant.hand.pace_log_sd == 0.1);
    CHECK(p.participant.hand.delay_mean_s == kPopulation.delay_mean_s);  // the rest as shipped
    // The person drawn from it: the population's speed, their own pace within its narrower spread.
    const Person a = draw_person(5, p.participant.hand);
    CHECK(a.slide_speed_mps == 0.07);
    CHECK(std::abs(std::log(a.pace)) < 5.0 * 0.1);
    // The force-alone pitch drift: the population's, everyone's, and a protocol may turn it off.
    CHECK(a.angle_drift_rad_sqrt_m == kPopulation.angle_drift_rad_sqrt_m);
    CHECK(parse_protocol(with_hand(R"({"angle_drift_rad_sqrt_m": 0})"), "p.json").participant.hand.angle_drift_rad_sqrt_m == 0.0);
    CHECK_THROWS_WITH_AS(parse_protocol(with_hand(R"({"angle_drift_rad_sqrt_m": -0.1})"), "p.json"),
                         doctest::Contains("participant.hand.angle_drift_rad_sqrt_m: must lie in"), ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with_hand(R"({"speed": 0.07})"), "p.json"), doctest::Contains("participant.hand.speed: unknown key"),
                         ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with_hand(R"({"hold_back": 0.5})"), "p.json"),
                         doctest::Contains("participant.hand.hold_back: must lie in"), ExperimentError);
    CHECK_THROWS_WITH_AS(parse_protocol(with_hand(R"({"delay_min_s": 0.3, "delay_max_s": 0.2})"), "p.json"),
                         doctest::Contains("delay_min_s must not exceed delay_max_s"), ExperimentError);
}

TEST_CASE("people: a trial's pace is the person's, varied by the population's trial spread from the trial's seed") {
    const Person a = draw_person(42);
    HandPopulation q = kPopulation;
    q.trial_pace_log_sd = 0.0;
    CHECK(trial_pace(a, q, 7) == a.pace);  // no spread: exactly theirs
    q.trial_pace_log_sd = 0.2;
    CHECK(trial_pace(a, q, 7) == trial_pace(a, q, 7));
    // 4000 trials: the log pace's mean is the person's and its sd the spread, within 5 standard errors.
    const int n = 4000;
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double l = std::log(trial_pace(a, q, static_cast<std::uint64_t>(i) * 104729u + 3u) / a.pace);
        s += l, s2 += l * l;
    }
    const double m = s / n, sd = std::sqrt(s2 / n - m * m);
    CHECK(std::abs(m) < 5.0 * 0.2 / std::sqrt(n));
    CHECK(sd == doctest::Approx(0.2).epsilon(0.05));
}
