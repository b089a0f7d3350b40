// energy_table.hpp — where the energy comes from, term by term (haptics/energy_balance.hpp), on
// the seeds' own trials: seed 002's bump counting (the finger slid over the bumps, turned with the
// surface's slope, at the seed's 5 cm/s and at 10 cm/s) and seed 000's block task, through the
// servo and the simulated rig exactly as `contactlab experiment run` does (engine/experiments/).
// The passivity observer once counted the `turn` term as the loop's and faulted 14 % of seed 002's
// trials (41 % at 10 cm/s); the table shows that term beside what the loop itself made.
#pragma once

#include "haptics/energy_balance.hpp"

#include <string>
#include <vector>

namespace contactlab::bench {

struct EnergyRow {
    std::string task;          // "seed 002 bumps", "seed 000 block"
    double speed = 0.0;        // m/s, the hand along the surface
    int trials = 0;
    EnergyTerms mean;          // J per trial, each term summed over a trial, averaged over trials
    double peak_observer = 0.0;   // J, the observer's largest sum over the trials (what it reports on)
    double peak_with_turn = 0.0;  // J, the same sum had `turn` been counted (the observer before)
    double threshold = 0.0;       // J, the observer's report threshold (2 x max_force^2 / 2K)
    int faulted = 0;              // trials in which the servo faulted
    int would_fault = 0;          // trials whose sum with `turn` passed the threshold
};

std::vector<EnergyRow> energy_table(bool quick);

}  // namespace contactlab::bench
