// bench_wearable.cpp — the per-tick costs of seed 003's wearable platform (haptics/wearable/):
// the FSR estimation of Fig. 4 (Newton on eq. 8), the simulated plant's equilibrium, and a whole
// 1 ms of the simulated device (estimation + PD + ten 0.1 ms plant steps). Run:
//   build/tests/bench/bench_wearable --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include "haptics/wearable/rig.hpp"

#include <benchmark/benchmark.h>

#include <cmath>

using namespace contactlab::wearable;

namespace {

// A pressed, slightly tilted platform: the plant's equilibrium for cables shortened unequally.
Equilibrium pressed(const PlatformDef& p, const Mat6& k) {
    const Eigen::Vector3d l0 = inverse_kinematics(p, p.rest).l;
    return solve_equilibrium(p, k, l0 - Eigen::Vector3d(0.0007, 0.0006, 0.0008), p.rest);
}

void BM_estimate_newton(benchmark::State& state) {
    const PlatformDef p;
    const Mat6 k = finger_stiffness();
    const Equilibrium t = pressed(p, k);
    const Eigen::Vector3d fsr = fsr_model(inverse_kinematics(p, t.pose), t.tension);
    Pose previous = t.pose;
    previous(3) += 1e-3;  // one sample's worth of motion to converge from
    for (auto _ : state) {
        const Estimate e = estimate(EstimatorDef{}, p, k, fsr, previous);
        benchmark::DoNotOptimize(e.pose);
    }
}
BENCHMARK(BM_estimate_newton);

void BM_equilibrium(benchmark::State& state) {
    const PlatformDef p;
    const Mat6 k = finger_stiffness();
    const Equilibrium t = pressed(p, k);
    const Eigen::Vector3d lambda = inverse_kinematics(p, p.rest).l - Eigen::Vector3d(0.00071, 0.0006, 0.0008);
    for (auto _ : state) {
        const Equilibrium e = solve_equilibrium(p, k, lambda, t.pose);  // warm start, as in the plant
        benchmark::DoNotOptimize(e.pose);
    }
}
BENCHMARK(BM_equilibrium);

void BM_rig_one_ms_force_control(benchmark::State& state) {
    WearableRig rig(seed_fit_rig());
    rig.command_force(Eigen::Vector3d::Constant(0.3));
    rig.advance(0.3);  // settled
    for (auto _ : state) {
        rig.advance(1e-3);
        benchmark::DoNotOptimize(rig.plant().tension());
    }
}
BENCHMARK(BM_rig_one_ms_force_control)->Unit(benchmark::kMicrosecond);

// The same while the tensions follow the seed's Fig. 8 sine at 3 Hz: every plant step moves.
void BM_rig_one_ms_moving(benchmark::State& state) {
    WearableRig rig(seed_fit_rig());
    double t = 0.0;
    for (auto _ : state) {
        rig.command_force(Eigen::Vector3d::Constant(0.15 + 0.15 * std::sin(2.0 * 3.141592653589793 * 3.0 * t)));
        rig.advance(1e-3);
        t += 1e-3;
        benchmark::DoNotOptimize(rig.plant().tension());
    }
}
BENCHMARK(BM_rig_one_ms_moving)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
