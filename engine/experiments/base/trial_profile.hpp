// trial_profile.hpp — where a simulated run's wall time goes (`experiment run --profile`), by
// stage, per second of the trials' virtual time: what "N x real time" is made of.
//
// Why: a simulated study's speed is what decides whether a 1,000-participant power analysis
// takes minutes or hours, and the profile says which stage to make faster (the servo tick, the
// simulated rig, the hand paths, the person's reading of the traces, the files). Off by default;
// on, it reads the monotonic clock a few times a trial and five times a servo tick (StageClock,
// haptics/stage_clock.hpp), which costs a few per cent and changes no result: the rows and
// traces are the same bytes with and without it (tests/experiments/test_trial_profile.cpp).
//
// Each thread running trials has its own profile (set with ProfileScope); the run adds them up.
#pragma once

#include "haptics/stage_clock.hpp"

#include <cstdint>
#include <string>

namespace contactlab::experiments {

// Seconds of wall time by stage, and the virtual time they simulated.
struct TrialProfile {
    double stimulus = 0.0;     // scenes and hand paths (stimulus.hpp), the resting heights included
    double servo_scene = 0.0;  // the servo's copy of each trial's scene and its index (ServoScene)
    double device = 0.0;       // the simulated rig: read, write, and its dynamics over each tick
    double tick = 0.0;         // the servo tick: proxy, force law, observer, roller control
    double records = 0.0;      // tick records through the ring into the trial's trace
    double platform = 0.0;     // seed 003's simulated wearable platform (its own loop, 100 Hz link)
    double perception = 0.0;   // the rest of a trial: the person reading what was displayed
    double files = 0.0;        // rows, parts and traces written to disk
    double wall = 0.0;         // the participants' trials and files, all stages
    double virtual_s = 0.0;    // s of trial time simulated (servo ticks / rate, platform runs)
    std::uint64_t trials = 0;

    // The stages' sum (s): all but `wall`, which also holds the loops around them.
    double staged() const;
    TrialProfile& operator+=(const TrialProfile& o);
};

// The stages, in the order reports list them: a key (the bench JSON's), a label (the tables'),
// and the field. One list, so a stage added here is summed, added up and reported everywhere.
struct ProfileStage {
    const char* key;
    const char* label;
    double TrialProfile::*field;
};
inline constexpr ProfileStage kProfileStages[] = {
    {"servo_tick", "servo tick", &TrialProfile::tick},
    {"simulated_rig", "simulated rig (sim-cld)", &TrialProfile::device},
    {"tick_records", "tick records", &TrialProfile::records},
    {"servo_scene", "servo scene and index", &TrialProfile::servo_scene},
    {"stimulus", "stimulus and hand path", &TrialProfile::stimulus},
    {"wearable_platform", "wearable platform (sim-wearable)", &TrialProfile::platform},
    {"perception", "perception", &TrialProfile::perception},
    {"files", "files", &TrialProfile::files},
};

// The profile the calling thread's trials add to; null (the default) when not profiling.
TrialProfile* thread_profile();

// Sets the calling thread's profile for its lifetime, restoring the one before.
class ProfileScope {
public:
    explicit ProfileScope(TrialProfile* p);
    ~ProfileScope();
    ProfileScope(const ProfileScope&) = delete;
    ProfileScope& operator=(const ProfileScope&) = delete;

private:
    TrialProfile* previous_;
};

// Adds the wall time of its own lifetime to one stage of the thread's profile (nothing, and no
// clock read, when the thread is not profiling).
class StageTimer {
public:
    explicit StageTimer(double TrialProfile::*stage);
    ~StageTimer();
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

private:
    TrialProfile* profile_;
    double TrialProfile::*stage_;
    StageClock clock_;  // reads the clock only when profiling
};

// The profile as a table: ms of wall time per s of virtual time for each stage, its share, and
// the run's speed in x real time (per thread: the wall time is summed over the threads).
std::string profile_table(const TrialProfile& p);

}  // namespace contactlab::experiments
