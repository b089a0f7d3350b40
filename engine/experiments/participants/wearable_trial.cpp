// wearable_trial.cpp — seed 003's curvature trial on the simulated wearable platform
// (wearable_trial.hpp).
#include "engine/experiments/participants/wearable_trial.hpp"

#include "drivers/sim/wearable_tasks.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/base/trial_profile.hpp"
#include "engine/experiments/base/random_stream.hpp"
#include "haptics/wearable/rig.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::experiments {

TrialOutcome wearable_curvature_trial(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng) {
    constexpr double kDeg = 180.0 / 3.14159265358979323846;
    drivers::sim::CurvatureArcDef def;
    def.chord = p.chord;
    def.height = t.stimulus;
    def.speed = p.hand_speed;  // m/s: here the arc's speed under the still finger
    def.contact_force = kWearableContactForce;
    def.reverse = c.motion == "B";
    drivers::sim::CurvatureArcResult run;
    {
        StageTimer timer(&TrialProfile::platform);
        run = drivers::sim::curvature_arc(wearable::seed_fit_rig(), def);
    }
    if (TrialProfile* profile = thread_profile())  // each sample advanced the rig by one period
        profile->virtual_s += static_cast<double>(run.samples.size()) * def.sample_period;
    TrialOutcome o;
    o.valid = !run.fault;
    double lo = 1e9, hi = -1e9, first = -1.0, last = -1.0;  // deg, s
    for (const drivers::sim::CurvatureSample& s : run.samples) {
        if (!s.contact) continue;
        lo = std::min(lo, s.platform_tilt * kDeg);
        hi = std::max(hi, s.platform_tilt * kDeg);
        if (first < 0.0) first = s.t;
        last = s.t;
        o.peak_force = std::max(o.peak_force, s.platform_force);
    }
    o.touched = first >= 0.0;
    // The share of the sweep's samples (one per link period) with the finger on the arc.
    if (!run.samples.empty())
        o.contact_fraction = static_cast<double>(std::count_if(run.samples.begin(), run.samples.end(),
                                                               [](const drivers::sim::CurvatureSample& s) { return s.contact; })) /
                             static_cast<double>(run.samples.size());
    o.time_s = o.touched ? last - first : 0.0;
    // The swept range, felt with relative noise; the answer is the height whose range is nearest
    // as a ratio (the ideal observer for relative noise).
    const double swept = o.touched ? hi - lo : 0.0;  // deg
    const double felt = std::max(1e-6, swept * (1.0 + p.participant.tilt_range_noise * normal01(rng)));  // deg
    double best = 1e300, answer = p.stimuli.front();
    for (double h : p.stimuli)
        if (const double d = std::abs(std::log(felt / arc_slope_range_deg(p.chord, h))); d < best) {
            best = d;
            answer = h;
        }
    o.response = stimulus_label(p, answer);
    o.platform = run.samples;
    return o;
}

}  // namespace contactlab::experiments
