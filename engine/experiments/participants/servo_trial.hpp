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

#include <functional>
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

// A hand steering tick by tick (feel_hand.hpp): given the tick just recorded, sets the hand's
// intended sample one period later and returns true, or returns false when the trial is over.
using Steer = std::function<bool(const drivers::TickRecord& now, drivers::PathSample& next)>;

// A trial whose hand closes its loop: the rig is placed for `envelope` (the scripted path over
// the same stimulus, so the arm's base, reach and limits are those of the scripted trial), the
// finger starts at `start`, and `steer` writes the path as the trial goes, for at most `max_s`
// seconds of virtual time.
TrialTrace run_steered_trial(const Scene& scene, const drivers::HandPath& envelope, const drivers::PathSample& start,
                             bool contact_location, const Steer& steer, double max_s);

}  // namespace contactlab::experiments
