// feel_tasks.hpp — what the person does with the hand that moves by feel (feel_hand.hpp), per
// task: the strategy above the hand's loop, deciding from what they notice.
//
//   seed 000  reach down onto the block's top, slide along it at the speed that lets them stop
//             within the pad after their first cue (cues.hpp's exploration speed, times their own
//             pace), notice the edge through the same cues and lapses as the scripted person
//             (the contact element moving back on the pad, the force turning off the vertical,
//             contact lost) and, a reaction time later, tip round it: turn the finger with the
//             felt normal (0.35 rad ahead of it) and move along the felt tangent bent downward,
//             then down the far face at their free speed to the finish line. Nothing tells the
//             hand where the edge is; running past it before tipping takes the pad off the top.
//   seed 002  reach down onto the contour's start and slide along the felt tangent to its end,
//             pressing, the finger turned with the felt normal, at their free speed slowed
//             where the felt contour turns (the two-thirds power law of drawing movements,
//             Lacquaniti, Terzuolo & Viviani 1983: speed falls as curvature^(-1/3)) beyond
//             1 / 20 mm, and moving along the felt tangent turned on by the felt rate of turn
//             times the delay (a forward model of what the delay hides, Miall & Wolpert 1996).
#pragma once

#include "engine/experiments/participants/person.hpp"
#include "engine/experiments/participants/servo_trial.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"

#include <cstdint>

namespace contactlab::experiments {

struct FeelTrial {
    TrialTrace trace;
    // s: the timed window. Seed 000: the start line (first contact at or past it) to the finish
    // line (-1: not reached); seed 002: the slide's start to the pad's centre passing its end.
    double start = -1.0, end = -1.0;
    // The person the trial drew (the same for all a participant's trials): what they notice
    // reads their own thresholds.
    Person person;
};

// Seed 000 by feel. Draws from `rng` in the scripted person's order (the location and angle
// thresholds, the reaction time, the lapses), then the hand's own noise.
FeelTrial feel_contour_following(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng);

// Seed 002's slide by feel over `st` (the scripted stimulus: its scene, and its path as the rig's
// envelope and the slide's start and end in x), by a person drawn from `people`.
FeelTrial feel_slide(const HandPopulation& people, const Condition& c, const PlannedTrial& t, const Stimulus& st);

}  // namespace contactlab::experiments
