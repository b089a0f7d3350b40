// person.hpp — who one simulated participant is, for the hand that moves by feel
// (feel_hand.hpp): the parameters people differ in, drawn once per participant from
// PlannedTrial::person, so every trial of a participant has the same person and two
// participants differ as people do (seed 000's completion-time sds are 30-70 % of the means).
//
// Each parameter is named with its distribution and source in docs/experiments.md ("The hand
// that moves by feel"); kPopulation below holds the distributions' numbers.
#pragma once

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
};

// The population the people are drawn from: each parameter's mean (or median) and spread.
struct PersonPopulation {
    double delay_mean_s = 0.12, delay_sd_s = 0.02, delay_min_s = 0.08, delay_max_s = 0.20;  // normal, clipped
    double press_median_n = 0.7, press_log_sd = 0.2;                                        // log-normal
    double pace_log_sd = 0.3;                                                               // log-normal, median 1
    double force_noise_cv_mean = 0.1, force_noise_cv_sd = 0.02;                             // normal, at least 0.02
    double speed_noise_cv_mean = 0.15, speed_noise_cv_sd = 0.03;                            // normal, at least 0.03
};

inline constexpr PersonPopulation kPopulation{};

// The person of a participant's `person` seed (deterministic; a different stream from the
// trials' noise).
Person draw_person(std::uint64_t person_seed, const PersonPopulation& population = kPopulation);

}  // namespace contactlab::experiments
