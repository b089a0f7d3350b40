// servo_trial.cpp — a trial through the servo and the simulated rig (servo_trial.hpp).
#include "engine/experiments/participants/servo_trial.hpp"

#include "engine/experiments/base/trial_profile.hpp"

#include "drivers/servo_loop.hpp"
#include "drivers/sim/sim_cld_device.hpp"
#include "haptics/servo_scene.hpp"
#include "haptics/servo_tick.hpp"

#include <cmath>
#include <memory>
#include <optional>

namespace contactlab::experiments {

namespace {
// The largest tick buffer this thread's finished traces left behind (TrialTrace::~TrialTrace).
std::vector<drivers::TickRecord>& spare_ticks() {
    thread_local std::vector<drivers::TickRecord> spare;
    return spare;
}
}  // namespace

TrialTrace::~TrialTrace() {
    std::vector<drivers::TickRecord>& spare = spare_ticks();
    if (ticks.capacity() > spare.capacity()) spare.swap(ticks);
}

// The servo's parameters for a trial: the scene's force, and without contact location the
// roller held at the pad's centre.
static ServoParams trial_servo_params(const Scene& scene, bool contact_location) {
    ServoParams params;
    params.stiffness = scene.force.stiffness;
    params.max_force = scene.force.max_force;
    params.passivity = scene.force.passivity;
    if (!contact_location) params.roller_travel = 1e-9;  // m: the element held at the pad's centre
    return params;
}

TrialTrace run_servo_trial(const Scene& scene, const drivers::HandPath& path, bool contact_location) {
    TrialProfile* const profile = thread_profile();  // null unless `experiment run --profile`
    auto setup = std::make_optional<StageTimer>(&TrialProfile::servo_scene);
    drivers::sim::SimCldParams sp;
    sp.max_force = scene.force.max_force;
    drivers::sim::SimCldDevice dev(sp, path);
    const ServoParams params = trial_servo_params(scene, contact_location);
    const ServoConfig config = drivers::servo_config_for(dev, kTrialRate);
    ServoTick tick(config, params);
    tick.set_publish_snapshots(false);  // nobody reads them: the trial's records come through the ring
    tick.scenes().publish(std::make_unique<ServoScene>(scene));
    drivers::ServoLoop loop(dev, tick, 1.0 / kTrialRate);
    TrialTrace trace;
    trace.ticks.swap(spare_ticks());  // a finished trial's memory, if this thread has one
    trace.ticks.clear();
    if (!loop.start()) {
        trace.faulted = true;
        return trace;
    }
    const auto ticks = static_cast<std::uint64_t>(std::llround((path.end() - path.start()) * kTrialRate));
    trace.ticks.reserve(ticks);  // the loop writes a record a step into the trace (no ring): reserved
    loop.record_into(&trace.ticks);
    setup.reset();
    // Profiled, the loop's own stages (device, tick, ring) are timed by the loop; the rest of
    // this loop (taking the records off the ring into the trace) counts as records.
    drivers::ServoLoopStages stages;
    if (profile) loop.set_profile(&stages);
    StageClock clock;  // the whole loop, ns (read only when profiling)
    clock.start(profile != nullptr);
    for (std::uint64_t k = 0; k < ticks; ++k) {
        loop.step(1.0 / kTrialRate, true);
        trace.faulted |= trace.ticks.back().fault != ServoFault::none;
    }
    if (profile) {
        double all = 0.0;  // ns
        clock.lap(all);
        profile->device += stages.device * 1e-9;
        profile->tick += stages.tick * 1e-9;
        profile->records += (all - stages.device - stages.tick) * 1e-9;
        profile->virtual_s += static_cast<double>(ticks) / kTrialRate;
    }
    return trace;
}

TrialTrace run_steered_trial(const Scene& scene, const drivers::HandPath& envelope, const drivers::PathSample& start,
                             bool contact_location, const Steer& steer, double max_s) {
    TrialProfile* const profile = thread_profile();
    auto setup = std::make_optional<StageTimer>(&TrialProfile::servo_scene);
    drivers::sim::SimCldParams sp;
    sp.max_force = scene.force.max_force;
    drivers::sim::SimCldDevice dev(sp, envelope);
    // From here the hand's path is what it steers: the start, then a sample a tick.
    const auto ticks = static_cast<std::uint64_t>(std::llround(max_s * kTrialRate));
    drivers::HandPath path(std::vector<drivers::PathSample>{start});
    path.reserve(ticks + 2);
    dev.hand().set_path(std::move(path));
    const ServoParams params = trial_servo_params(scene, contact_location);
    const ServoConfig config = drivers::servo_config_for(dev, kTrialRate);
    ServoTick tick(config, params);
    tick.set_publish_snapshots(false);  // nobody reads them: the hand steers from the trial's records
    tick.scenes().publish(std::make_unique<ServoScene>(scene));
    drivers::ServoLoop loop(dev, tick, 1.0 / kTrialRate);
    TrialTrace trace;
    trace.ticks.swap(spare_ticks());
    trace.ticks.clear();
    if (!loop.start()) {
        trace.faulted = true;
        return trace;
    }
    trace.ticks.reserve(ticks);  // at most a record a step, written by the loop
    loop.record_into(&trace.ticks);
    setup.reset();
    drivers::ServoLoopStages stages;
    if (profile) loop.set_profile(&stages);
    StageClock clock;
    clock.start(profile != nullptr);
    std::uint64_t k = 0;
    for (bool going = true; going && k < ticks; ++k) {
        loop.step(1.0 / kTrialRate, true);
        const drivers::TickRecord& r = trace.ticks.back();
        trace.faulted |= r.fault != ServoFault::none;
        drivers::PathSample next;
        going = steer(r, next);
        if (!going) continue;  // the loop ends here, with this step counted in k
        // The sample is for the next tick; a later one than the path's last, always.
        next.t = std::max(next.t, dev.hand().path().end() + 1e-9);
        dev.hand().steer(next);
    }
    if (profile) {
        double all = 0.0;
        clock.lap(all);
        profile->device += stages.device * 1e-9;
        profile->tick += stages.tick * 1e-9;
        profile->records += (all - stages.device - stages.tick) * 1e-9;
        profile->virtual_s += static_cast<double>(k) / kTrialRate;
    }
    return trace;
}

}  // namespace contactlab::experiments
