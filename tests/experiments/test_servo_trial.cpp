// test_servo_trial.cpp — one trial through the servo and the simulated rig (servo_trial.hpp):
// a trial run after others on the same thread, which reuses their tick buffer, records exactly
// what the same trial records on a thread of its own.
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/participants/servo_trial.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "process.hpp"

#include <doctest/doctest.h>

#include <string>
#include <thread>

using namespace contactlab::experiments;

namespace {
std::string protocol_path(const char* name) { return (cli_test::source_dir() / "scenes" / "experiments" / name).string(); }

Stimulus stimulus(const Protocol& p, int bumps, std::uint64_t seed) {
    PlannedTrial t;
    t.stimulus = bumps;
    t.seed = seed;
    return make_stimulus(p, p.conditions[0], t);
}
}  // namespace

TEST_CASE("servo trial: after other trials on the same thread, the same records as on a thread of its own") {
    const Protocol p = load_protocol(protocol_path("002-bump-counting.json"));
    const Stimulus a = stimulus(p, 4, 11), b = stimulus(p, 1, 12);
    // On a fresh thread: no earlier trial's buffer to reuse.
    TrialTrace alone;
    std::thread([&] { alone = run_servo_trial(b.scene, b.path, true); }).join();
    // Here, after two trials whose traces were dropped (their buffers handed on).
    { const TrialTrace first = run_servo_trial(a.scene, a.path, true); REQUIRE(first.ticks.size() > 1000); }
    { const TrialTrace second = run_servo_trial(a.scene, a.path, false); REQUIRE_FALSE(second.ticks.empty()); }
    const TrialTrace after = run_servo_trial(b.scene, b.path, true);
    REQUIRE(after.ticks.size() == alone.ticks.size());
    CHECK(after.faulted == alone.faulted);
    int differ = 0;
    for (std::size_t i = 0; i < after.ticks.size(); ++i) {
        const auto& x = after.ticks[i];
        const auto& y = alone.ticks[i];
        const bool same = x.tick == y.tick && x.t == y.t && x.finger == y.finger && x.phi == y.phi && x.roller_l == y.roller_l &&
                          x.proxy == y.proxy && x.contact == y.contact && x.depth == y.depth && x.force == y.force &&
                          x.l_d == y.l_d && x.roller_target == y.roller_target && x.observer_energy == y.observer_energy &&
                          x.state == y.state && x.fault == y.fault;
        differ += same ? 0 : 1;
    }
    CHECK(differ == 0);
    // 4.08 s of hand path at the servo's 1 kHz (0.3 s down, 0.3 s settling, 0.164 m at 5 cm/s, a 0.2 s hold).
    CHECK(static_cast<double>(after.ticks.size()) == doctest::Approx(4080.0).epsilon(3.0 / 4080.0));
}
