// rig_tuning.hpp — the parts of seed 003's rig a user tunes while it runs (the editor's Wearable
// section, issue 29): the force loop's and the position loop's PD gains (Figs. 5-6), the fit mode
// (the seed's measured 45 ms response, or Table 1's motor alone: rig.hpp's seed_fit_rig) and the
// FSR noise. The same limits for every caller, so a refused value is refused everywhere.
#pragma once

#include "haptics/wearable/rig.hpp"

#include <string>

namespace contactlab::wearable {

struct RigTuning {
    double force_kp = ForceControlDef{}.kp;        // N m of motor torque per N of tension error
    double force_kd = ForceControlDef{}.kd;        // N m per N/s
    double position_kp = PositionControlDef{}.kp;  // N m per m of cable-length error
    double position_kd = PositionControlDef{}.kd;  // N m per m/s
    bool seed_fit = true;    // true: references shaped to the seed's 3.5 Hz (seed_fit_rig); false: none
    double fsr_noise = 0.0;  // N, standard deviation of each FSR reading's noise
    bool operator==(const RigTuning&) const = default;
};

inline constexpr double kMaxFsrNoise = 0.1;  // N: as `simulate --fsr-noise` (10x the FSRs' 10 mN class)

// The reference time constant of the seed fit (s): 1 / (2 pi 3.5 Hz), as seed_fit_rig() sets it.
double seed_fit_time_constant();

RigTuning tuning_of(const RigDef& def);
void apply_tuning(RigDef& def, const RigTuning& t);
// "" when usable, else why not ("force_kp: must be a finite number >= 0, got -1"): gains
// finite and >= 0, FSR noise in [0, kMaxFsrNoise] N.
std::string rig_tuning_problem(const RigTuning& t);

}  // namespace contactlab::wearable
