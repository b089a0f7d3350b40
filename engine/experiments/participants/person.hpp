// person.hpp — who one simulated participant is, for the hand that moves by feel
// (feel_hand.hpp): the parameters people differ in, drawn once per participant from
// PlannedTrial::person, so every trial of a participant has the same person and two
// participants differ as people do (seed 000's completion-time sds are 30-70 % of the means).
//
// Each parameter is named with its distribution and source in docs/experiments.md ("The hand
// that moves by feel"); kPopulation below holds the distributions' numbers.
#pragma once

#include "engine/experiments/protocol/protocol.hpp"

#include <cstdint>

namespace contactlab::experiments {

struct Person {
    // Sensorimotor delay of the hand's feedback on touch (s): what it feels acts on the hand this
    // much later. People correct a finger's force and motion from touch about 100 ms after
    // it changes (Jenmalm & Johansson 1997; 60-90 ms for grip, Cole & Abbs 1988), voluntary
    // corrections of a moving arm 100-150 ms (Johansson & Flanagan 2009).
    double delay_s = 0.12;
    // The normal force the person presses with while exploring (N).
    double press_force_n = 0.7;
    // Their own pace: multiplies the speeds their strategy chooses.
    double pace = 1.0;
    // Signal-dependent motor noise: sd of the force as a share of the force pressed, and of the
    // speed as a share of the speed (Harris & Wolpert 1998; Jones, Hamilton & Wolpert 2002).
    double force_noise_cv = 0.1;
    double speed_noise_cv = 0.15;
    // The population's, the same for everyone: seed 002's free speed at the median pace (m/s)
    // and the guarded slide's hold-back (a multiple of the press force).
    double slide_speed_mps = 0.08;
    double hold_back = 2.0;
    // The finger's unfelt pitch drift where the strategy lets it drift (rad per sqrt(m) travelled).
    double angle_drift_rad_sqrt_m = 0.0;
    // Their own force-direction threshold less the participant model's (deg): people differ in
    // how far the force must turn before they notice it.
    double angle_threshold_offset_deg = 0.0;
};

// The population the people are drawn from (protocol.hpp's HandPopulation, a protocol's
// `participant.hand`): each parameter's mean (or median) and spread.
using PersonPopulation = HandPopulation;
inline constexpr PersonPopulation kPopulation{};

// This trial's pace: the person's, varied from trial to trial by the population's
// trial_pace_log_sd (log-normal, median their own), from the trial's seed (its own stream: the
// trial's other draws are unchanged). Exactly theirs, drawing nothing, when that sd is 0.
double trial_pace(const Person& person, const HandPopulation& population, std::uint64_t trial_seed);

// The person of a participant's `person` seed (deterministic; a different stream from the
// trials' noise).
Person draw_person(std::uint64_t person_seed, const PersonPopulation& population = kPopulation);

}  // namespace contactlab::experiments
