// bench_trial.cpp — a simulated seed 002 trial's parts, per trial (the shipped protocol's first
// F+CLD trials, stimuli 0-4): the stimulus and its hand path (the resting heights), the trial
// through the servo and the rig (run_servo_trial), and the whole trial with the person's
// perception (perform_sim_trial). `contactlab experiment run --profile` gives the same split for
// a whole run; this isolates each part for a change. Run:
//   build/tests/bench/bench_trial --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "engine/experiments/participants/servo_trial.hpp"
#include "engine/experiments/participants/sim_participant.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"

#include <benchmark/benchmark.h>

using namespace contactlab::experiments;

namespace {

const Protocol& seed002() {
    static const Protocol p = load_protocol(CONTACTLAB_SEED002_PROTOCOL);
    return p;
}

// The first trial of the participant's F+CLD block showing `bumps` bumps.
PlannedTrial trial_with(int bumps) {
    for (const auto& block : plan_trials(seed002(), 1, 1))
        for (const PlannedTrial& t : block)
            if (seed002().conditions[static_cast<std::size_t>(t.condition)].contact_location && t.stimulus == bumps) return t;
    return plan_trials(seed002(), 1, 1).front().front();
}

void BM_seed002_hand_path(benchmark::State& state) {
    const PlannedTrial t = trial_with(static_cast<int>(state.range(0)));
    const Condition& c = seed002().conditions[static_cast<std::size_t>(t.condition)];
    for (auto _ : state) {
        const Stimulus st = make_stimulus(seed002(), c, t);
        benchmark::DoNotOptimize(st.path.end());
    }
}
BENCHMARK(BM_seed002_hand_path)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

void BM_seed002_servo_and_rig(benchmark::State& state) {
    const PlannedTrial t = trial_with(static_cast<int>(state.range(0)));
    const Condition& c = seed002().conditions[static_cast<std::size_t>(t.condition)];
    const Stimulus st = make_stimulus(seed002(), c, t);
    double virtual_s = 0.0;
    for (auto _ : state) {
        const TrialTrace tr = run_servo_trial(st.scene, st.path, c.contact_location);
        benchmark::DoNotOptimize(tr.ticks.data());
        virtual_s += st.path.end() - st.path.start();
    }
    state.counters["x_real_time"] = benchmark::Counter(virtual_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_seed002_servo_and_rig)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

void BM_seed002_whole_trial(benchmark::State& state) {
    const PlannedTrial t = trial_with(static_cast<int>(state.range(0)));
    double rows_s = 0.0;
    for (auto _ : state) {
        const TrialOutcome o = perform_sim_trial(seed002(), t);
        benchmark::DoNotOptimize(o.response.data());
        rows_s += o.time_s;
    }
    // The goal's measure: the rows' time_s over wall time (500x).
    state.counters["x_rows_time"] = benchmark::Counter(rows_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_seed002_whole_trial)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
