// person.cpp — drawing a simulated person (person.hpp).
#include "engine/experiments/participants/person.hpp"

#include "engine/experiments/base/random_stream.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::experiments {

Person draw_person(std::uint64_t person_seed, const PersonPopulation& q) {
    std::uint64_t rng = mix64(person_seed ^ 0xFEE1ull);
    Person p;
    // Draws in this order, each new parameter's at the end, so adding one keeps these people.
    p.delay_s = std::clamp(q.delay_mean_s + q.delay_sd_s * normal01(rng), q.delay_min_s, q.delay_max_s);
    p.press_force_n = q.press_median_n * std::exp(q.press_log_sd * normal01(rng));
    p.pace = std::exp(q.pace_log_sd * normal01(rng));
    p.force_noise_cv = std::max(0.02, q.force_noise_cv_mean + q.force_noise_cv_sd * normal01(rng));
    p.speed_noise_cv = std::max(0.03, q.speed_noise_cv_mean + q.speed_noise_cv_sd * normal01(rng));
    p.slide_speed_mps = q.slide_speed_mps;
    p.hold_back = q.hold_back;
    p.angle_drift_rad_sqrt_m = q.angle_drift_rad_sqrt_m;
    // A sixth draw, after the five above: the same people as before it, each now with their own
    // threshold.
    p.angle_threshold_offset_deg = q.angle_threshold_sd_deg * normal01(rng);
    return p;
}

double trial_pace(const Person& person, const HandPopulation& q, std::uint64_t trial_seed) {
    if (q.trial_pace_log_sd <= 0.0) return person.pace;
    std::uint64_t rng = mix64(trial_seed ^ 0x9ACEull);
    return person.pace * std::exp(q.trial_pace_log_sd * normal01(rng));
}

}  // namespace contactlab::experiments
