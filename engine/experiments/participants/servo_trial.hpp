// servo_trial.hpp — one trial through the real servo (haptics/servo_tick.hpp) and seed 000's
// simulated rig (drivers/sim/sim_cld_device.hpp) held by a scripted hand, in virtual time: what
// the device displayed, tick by tick, is what the simulated participant perceives.
//
// A force-only condition holds the contact element at the pad's centre by letting the servo use
// 1 nm of roller travel (seed 002: "the roller position is fixed at the center"); the force is
// the same in both conditions.
#pragma once

#include "drivers/hand_path.hpp"
#include "drivers/tick_record.hpp"
#include "haptics/scene.hpp"

#include <vector>

namespace contactlab::experiments {

inline constexpr double kTrialRate = 1000.0;  // Hz, the seeds' servo rate
// The rig's name (drivers::sim::SimCldDevice::name()), for the results' `device` column and meta.
inline constexpr const char* kTrialDevice = "sim-cld";

struct TrialTrace {
    std::vector<drivers::TickRecord> ticks;  // one per servo tick
    bool faulted = false;                    // the servo reported a fault (the trial is invalid)

    TrialTrace() = default;
    TrialTrace(const TrialTrace&) = default;
    TrialTrace(TrialTrace&&) noexcept = default;
    TrialTrace& operator=(const TrialTrace&) = default;
    TrialTrace& operator=(TrialTrace&&) noexcept = default;
    // Hands the ticks' memory to this thread's next run_servo_trial: a trial's ~4,000 records
    // (~0.7 MB) were allocated, page-faulted in and returned to the system every trial, 5 % of a
    // simulated seed 002 participant.
    ~TrialTrace();
};

TrialTrace run_servo_trial(const Scene& scene, const drivers::HandPath& path, bool contact_location);

}  // namespace contactlab::experiments
