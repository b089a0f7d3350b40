// wearable_trial.hpp — a trial of seed 003's curvature task on seed 003's own device, the
// simulated wearable fingertip platform (protocol `"device": "sim-wearable"`), as the seed ran it:
// the finger held still, the virtual arc moving under it, the platform tilted by its position
// controller to the arc's slope under the contact and pressed with the contact force
// (drivers/sim/wearable_tasks.hpp, curvature_arc, with the seed-fitted rig).
//
// Task A moves the arc under the finger one way, task B the other way (the condition's `motion`;
// seed 003's S_1 E_1 and S_2 E_2). The simulated participant reads the platform's tilt: the range it swept
// while in contact, felt with relative noise (ParticipantModel::tilt_range_noise), and answers
// the height whose range is nearest as a ratio: 2 asin(d / 2 r_a) (arc_slope_range_deg). The range of slope is the cue because people judge a curvature by the
// difference in slope across what they touch (Pont, Kappers and Koenderink 1999, Perception &
// Psychophysics 61(5)); the noise's size is this model's choice, not a fitted value.
#pragma once

#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/participants/trial_outcome.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"

#include <cstdint>

namespace contactlab::experiments {

// The normal force (N) the platform presses with while the arc is under the finger; the seed's
// participants felt the arc at a comfortable force it does not state.
inline constexpr double kWearableContactForce = 0.5;
// Hz: the host's references reach the platform over its serial link at this rate (seed 003), one
// trace row each.
inline constexpr double kWearableLinkRate = 100.0;

// Fills response, time_s (the contact's duration), touched, peak_force (the fingertip wrench's
// force on the platform), valid (no control or estimate fault) and `platform` (the trace).
TrialOutcome wearable_curvature_trial(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng);

}  // namespace contactlab::experiments
