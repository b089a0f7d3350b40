// energy_table.cpp — the energy terms on the seeds' trials (see energy_table.hpp).
#include "engine/bench/energy_table.hpp"

#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/participants/servo_trial.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "engine/experiments/base/random_stream.hpp"
#include "haptics/servo_tick.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::bench {
namespace {

// A condition with contact location displayed (the field defaults for the rest).
experiments::Condition with_contact_location(const char* name) {
    experiments::Condition c;
    c.name = name;
    c.contact_location = true;
    return c;
}

// Seed 002's protocol on the text's 20 cm base (scenes/experiments/002-bump-counting-20cm.json,
// the base whose steep flanks turn the finger most): R 20 mm and 1300 N/m where it differs from
// experiments::Protocol's defaults (L 20 mm, 1.5 N, bumps 3 and 18 mm over 18.4 cm, pressed 3 mm,
// base span 20 cm), with contact location.
experiments::Protocol seed_002(double speed) {
    experiments::Protocol p;
    p.task = experiments::Task::bump_counting;
    p.conditions = {with_contact_location("F+CLD")};
    p.hand_speed = speed;
    p.finger_radius = 0.020;
    p.stiffness = 1300.0;
    return p;
}

// Seed 000's contour following (scenes/experiments/000-contour-following.json): the block task at
// the defaults (R 26 mm, L 20 mm, 1000 N/m, 1.5 N, 5 cm/s pressed 3 mm, finish 6 cm down).
experiments::Protocol seed_000() {
    experiments::Protocol p;
    p.task = experiments::Task::contour_following;
    p.conditions = {with_contact_location("force+cld")};
    return p;
}

EnergyRow run_rows(const std::string& task, const experiments::Protocol& p, const std::vector<double>& stimuli) {
    EnergyRow row;
    row.task = task;
    row.speed = p.hand_speed;
    // The servo's: passivity_threshold times the spring's linear-range energy, F^2 / 2K (J), and the
    // observer's leak (0.5 s, servo_tick.cpp) over one tick of the trials' rate, for the sum the
    // observer would have kept with `turn` counted (its own sum is in each record).
    row.threshold = ServoParams{}.passivity_threshold * p.max_force * p.max_force / (2.0 * p.stiffness);
    const double keep = std::exp(-1.0 / (experiments::kTrialRate * 0.5));
    for (std::size_t i = 0; i < stimuli.size(); ++i) {
        experiments::PlannedTrial t;
        t.stimulus = stimuli[i];
        t.seed = experiments::mix64(0xE5E5 + i);
        const experiments::Stimulus st = experiments::make_stimulus(p, p.conditions[0], t);
        const experiments::TrialTrace tr = experiments::run_servo_trial(st.scene, st.path, true);
        double sum_turn = 0.0, peak = 0.0, peak_turn = 0.0;  // J
        for (const auto& r : tr.ticks) {
            const EnergyTerms& e = r.energy;
            row.mean.hold += e.hold;
            row.mean.field += e.field;
            row.mean.turn += e.turn;
            row.mean.edit += e.edit;
            row.mean.proxy += e.proxy;
            row.mean.friction += e.friction;
            row.mean.damping += e.damping;
            sum_turn = sum_turn * keep + e.generated() + e.turn;
            peak = std::max(peak, r.observer_energy);
            peak_turn = std::max(peak_turn, sum_turn);
        }
        row.peak_observer = std::max(row.peak_observer, peak);
        row.peak_with_turn = std::max(row.peak_with_turn, peak_turn);
        row.faulted += tr.faulted ? 1 : 0;
        row.would_fault += peak_turn > row.threshold ? 1 : 0;
        ++row.trials;
    }
    const double n = std::max(1, row.trials);
    for (double* v : {&row.mean.hold, &row.mean.field, &row.mean.turn, &row.mean.edit, &row.mean.proxy,
                      &row.mean.friction, &row.mean.damping})
        *v /= n;
    return row;
}

}  // namespace

std::vector<EnergyRow> energy_table(bool quick) {
    // Every bump count the protocol presents, each a new random stimulus (quick: fewer).
    std::vector<double> bumps;
    for (int rep = 0; rep < (quick ? 1 : 4); ++rep)
        for (int k = 0; k <= 4; ++k) bumps.push_back(k);
    std::vector<EnergyRow> rows;
    rows.push_back(run_rows("seed 002 bumps", seed_002(0.05), bumps));
    rows.push_back(run_rows("seed 002 bumps", seed_002(0.10), bumps));
    rows.push_back(run_rows("seed 000 block", seed_000(), quick ? std::vector<double>{0.07} : std::vector<double>{0.04, 0.07, 0.10}));
    return rows;
}

}  // namespace contactlab::bench
