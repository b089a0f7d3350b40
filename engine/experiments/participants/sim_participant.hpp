// sim_participant.hpp — the simulated participant (`--participant sim`): performs a trial
// through the real servo and the simulated rig (servo_trial.hpp) with a scripted hand, and
// answers from what the device displayed: the force's direction and size at the finger, and the
// contact element's position on the pad (held at the centre in force-only conditions). Each cue
// is read through a threshold with Gaussian perceptual noise (ParticipantModel, protocol.hpp),
// drawn from the trial's seed, so a participant's answers are reproducible.
//
//   contour-following  slides along the top at the speed the person's cues allow (the pad left
//                      beyond the first cue over `stop_time_s`), and runs the slide once to find
//                      when the edge is noticed: the element moving `location_threshold_mm` back
//                      on the pad (contact location shown), else the force turning
//                      `force_angle_threshold_deg` off the vertical, or contact lost, outside
//                      the trial's attention lapses; after the trial's reaction time the finger
//                      tips round the edge. The trial is run again with that overshoot and timed
//                      from the start line (d from the edge) to the finish line; it fails if
//                      contact breaks (seed 000).
//   bump-counting      counts the bumps felt through the arm: where the finger's height rises
//                      above its mean over +-12 mm of travel by a noisy threshold and the path
//                      turns over a top there (not the flank of a valley); the rise-and-fall
//                      swings of the force's direction (and, with contact location, of the
//                      element's position) over a bump's width (means over 4 mm of travel less
//                      means over 16 mm) beyond their noisy thresholds are the same bump within a
//                      pad length of such a rise, and bumps of their own elsewhere (one per pad
//                      length); a rise or swing during a lapse is not felt; answers 0..4 (seed 002)
//   curvature          the force direction's range over the slide, with noise, against the range
//                      each height would give (arc_slope_range_deg): the nearest height (seed 003)
//   surface-orientation the force's growth per mm along each downward diagonal, each with
//                      `stiffness_noise` relative noise: the softer diagonal is the compliant
//                      axis a1, 45 deg (template A) or 135 deg (B) (seed 004)
//   edge-sharpness     slides over both intervals' edges and reads, from each, the peak rate of
//                      change (per mm of travel, over a 4 mm running mean) of the force's
//                      direction and, with contact location shown, of the contact element's
//                      position: over an edge of radius r the contact normal turns at 1 / (r + R)
//                      per mm of the finger's centre (R the finger's radius), so a sharper edge
//                      turns both faster. Each felt rate carries `edge_rate_noise` relative
//                      (Weber) noise; the edge whose rates felt larger, by the mean of the log
//                      ratios over the cues it has, is answered sharper. Two cues with
//                      independent noise average to a smaller noise: that is what contact
//                      location adds here.
//
// Room engine/experiments/participants/: who answers a trial: the simulated person (here), the model observer, a
// trial through the servo (servo_trial.hpp) or on the wearable platform (wearable_trial.hpp), and
// what a trial gave (trial_outcome.hpp). Includes protocol/ and base/ (not procedures/, its sibling).
// The rooms and their arrows: docs/ARCHITECTURE.md, "The experiments' rooms".
#pragma once

#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "engine/experiments/participants/trial_outcome.hpp"

#include <string>
#include <vector>

namespace contactlab::experiments {

TrialOutcome perform_sim_trial(const Protocol& p, const PlannedTrial& t);

}  // namespace contactlab::experiments
