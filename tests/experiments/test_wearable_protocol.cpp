// test_wearable_protocol.cpp — seed 003's protocol on seed 003's device, the simulated wearable
// platform (engine/experiments/participants/wearable_trial.hpp): rows say sim-wearable, traces hold the
// platform's tilt, press force and cable tensions, the tilt follows the arc's slope, and a
// participant without noise answers every height right.
#include "engine/experiments/runs/experiment_run.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/runs/run_meta.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/participants/wearable_trial.hpp"
#include "process.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace contactlab::experiments;
using cli_test::TempDir;

namespace {

Protocol wearable_protocol() {
    Protocol p = load_protocol((cli_test::source_dir() / "scenes/experiments/003-curvature.json").string());
    p.repetitions = 1;  // each height once per task: 6 trials
    return p;
}

// Rows of a trace CSV as numbers, with its header.
std::vector<std::vector<double>> read_trace(const std::string& path, std::string& header) {
    std::ifstream in(path);
    std::getline(in, header);
    std::vector<std::vector<double>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<double> r;
        std::stringstream s(line);
        for (std::string cell; std::getline(s, cell, ',');) r.push_back(std::stod(cell));
        rows.push_back(r);
    }
    return rows;
}

}  // namespace

TEST_CASE("wearable protocol: seed 003's arcs on the simulated platform, rows and traces") {
    Protocol p = wearable_protocol();
    p.participant.tilt_range_noise = 0.0;  // the answer is then the platform's own range's nearest
    TempDir dir;
    RunOptions o;
    o.participants = {1};
    o.output = dir.file("r.csv");
    const RunSummary s = run_experiment(p, o);
    CHECK(s.rows == 6);
    CHECK(s.invalid == 0);
    const ResultsTable t = read_results_csv(o.output);
    const std::size_t device = *t.column("device"), correct = *t.column("correct"), touched = *t.column("touched");
    const std::size_t cond = *t.column("condition"), stim = *t.column("stimulus"), trial = *t.column("trial");
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
        CAPTURE(i);
        CHECK(t.rows[i][device] == "sim-wearable");
        CHECK(t.rows[i][touched] == "1");
        // The platform sweeps within 10 % of the arc's slope range (the seed-fitted rig lags its
        // references by 45 ms: 0.7 deg at the chord's ends at 10 cm/s, and task A starts with a
        // step to the arc's end slope), and the heights' ranges stand 1.5x and 2x apart: without
        // noise every answer is right.
        CHECK(t.rows[i][correct] == "1");
        std::string header;
        const auto rows = read_trace(dir.file("r.csv.traces/sim1-" + t.rows[i][cond] + "-" + t.rows[i][trial] + ".csv"), header);
        CHECK(header == "t,contact_x,surface_angle,tilt,force,q1,q2,q3,contact,fault");
        double lo = 1e9, hi = -1e9, peak_force = 0.0, min_tension = 1e9;
        for (const auto& r : rows) {
            REQUIRE(r.size() == 10);
            if (r[8] != 1.0) continue;
            lo = std::min(lo, r[3]), hi = std::max(hi, r[3]);
            peak_force = std::max(peak_force, r[4]);
            min_tension = std::min({min_tension, r[5], r[6], r[7]});
        }
        const double h = std::stod(t.rows[i][stim]) * 1e-3;  // m
        const double want = arc_slope_range_deg(p.chord, h);
        CAPTURE(want);
        CHECK((hi - lo) * 180.0 / 3.14159265358979 == doctest::Approx(want).epsilon(0.10));
        // Pressed with the contact force (0.5 N) through cables that stay taut.
        CHECK(peak_force == doctest::Approx(kWearableContactForce).epsilon(0.2));
        CHECK(min_tension > 0.0);
    }
    // The provenance names the device and its link rate.
    const auto meta = read_meta(o.output);
    REQUIRE(meta);
    CHECK((*meta)["device"] == "sim-wearable");
    CHECK((*meta)["servo_rate_hz"].get<double>() == 100.0);
}

TEST_CASE("wearable protocol: the arc's slope range, and sim-wearable is for the curvature task only") {
    // Seed 003 section 4: r_a = (d^2 / 4 + h^2) / (2 h); at h = 30 mm, d = 30 cm: 0.39 m, slopes +-22.6 deg.
    CHECK(arc_slope_range_deg(0.30, 0.03) == doctest::Approx(2.0 * std::asin(0.15 / 0.39) * 180.0 / 3.14159265358979));
    const std::string bumps = R"({"format": "contactlab experiment protocol", "version": 1, "name": "x", "seed": "002",
      "task": "bump-counting", "device": "sim-wearable", "conditions": [{"name": "F"}], "stimuli": [0, 1], "answers": ["0", "1"]})";
    CHECK_THROWS_WITH_AS(parse_protocol(bumps, "p.json"), doctest::Contains("p.json: device: sim-wearable runs the curvature task only"),
                         ExperimentError);
    const std::string falcon = R"({"format": "contactlab experiment protocol", "version": 1, "name": "x", "seed": "003",
      "task": "curvature", "device": "falcon", "conditions": [{"name": "A", "motion": "A"}], "stimuli": [0.01, 0.02], "answers": ["10", "20"]})";
    CHECK_THROWS_WITH_AS(parse_protocol(falcon, "p.json"), doctest::Contains("p.json: device: expected \"sim-cld\""), ExperimentError);
}
