// feel_hand.hpp — a hand that closes its loop on what it feels (`hand.model` "feel").
//
// Each servo tick it is told what the device displayed (the force on the finger and whether it
// touched, the contact element's place on the pad, the finger's position and angle from the
// arm), and it sets where the hand means the finger to be one tick later; the rig's hand
// impedance (drivers/sim/scripted_hand.hpp) pulls the finger there. It knows nothing of the
// contour ahead. Its structure is the contour-following exploratory procedure (Lederman &
// Klatzky 1987): keep touching, move along the surface, regulate the normal force:
//
//   * what it feels reaches the hand `Person::delay_s` late (a delay line of tick records);
//   * the felt normal is the force's direction (the last one while out of contact), the felt
//     tangent is the normal turned -90 deg (the direction of travel, +x on a floor);
//   * it moves along the felt tangent at the commanded speed, turned `turn` rad further into
//     the surface when the strategy expects the contour to turn (tipping round an edge: the
//     felt tangent lags the real one by the delay times the rate of turn), the speed changing
//     with a 0.15 s time constant;
//   * it presses along the felt normal: the intended position moves into the surface at
//     `gain` (F* - F) m/s, an integral force controller whose gain times the delay times the
//     hand-surface stiffness is 0.4 rad, well inside the delayed integrator's stability limit
//     of pi / 2; out of contact it goes back toward where the surface was at `gain` F*;
//   * motor noise grows with what it is asked to do (signal-dependent noise, Harris & Wolpert
//     1998): the speed varies by `speed_noise_cv` of itself, the press by `force_noise_cv` of
//     F*, each as 0.05 s low-pass Gaussian noise (the muscles' own filtering);
//   * the finger's angle is the person's: held where the strategy says, or turned with the felt
//     normal (keeping the contact on the pad) once the strategy turns it.
//
// The task's strategy (feel_tasks.hpp) sets the speed, the bias and the angle from what the
// person has noticed; this class is the loop beneath it. Deterministic given its seed.
#pragma once

#include "drivers/hand_path.hpp"
#include "drivers/tick_record.hpp"
#include "engine/experiments/participants/person.hpp"

#include <cstdint>
#include <vector>

namespace contactlab::experiments {

class FeelHand {
public:
    // `start`: the finger's centre (m) and angle (rad) when the trial begins, at time 0;
    // `dt` the servo period (s); `noise_seed` this trial's motor noise.
    FeelHand(const Person& person, drivers::PathSample start, double dt, std::uint64_t noise_seed);

    // The tick just recorded (what the device displayed, read at now.t). Returns the intended
    // finger position and angle for the end of the device's next period (now.t + 2 dt).
    drivers::PathSample step(const drivers::TickRecord& now);

    // What the strategy commands.
    void set_speed(double v) { speed_goal_ = v; }  // m/s along the felt tangent
    void set_turn(double a) { turn_ = a; }         // rad, the felt tangent turned toward the surface
    void hold_angle(double phi) { follow_ = false, phi_goal_ = phi; }  // rad
    // Turn the finger with the felt normal, `lead` (rad) further round (tipping ahead of it).
    void follow_normal(double lead) { follow_ = true, lead_ = lead; }
    // Descend toward the surface at `v` (m/s) until contact is felt, instead of the force loop's
    // slower approach (people reach for a surface faster than they press on it).
    void set_approach(double v) { approach_ = v; }
    // Guarded sliding (the default): pushing against more than the target force, the hand holds
    // back its advance (fully at twice the target) until the press and the felt normal have
    // caught up with a surface that rose ahead of it. Off while the strategy means to press into
    // the surface (tipping round seed 000's edge, where the force rises by intent).
    void set_guarded(bool on) { guard_ = on; }
    // Let the finger's angle drift from the one the hand means, as a random walk with the
    // hand's travel of the person's angle_drift_rad_sqrt_m (a posture held without feeling where
    // on the pad the contact is: seed 000 without contact location). Its own noise stream: the
    // rest of the trial's noise is unchanged.
    void set_drifting(bool on) { drifting_ = on; }

    // What the hand has felt so far, `delay_s` late.
    bool felt_contact() const { return felt_contact_; }
    double felt_force() const { return felt_force_; }  // N, along the felt normal
    Vec2 felt_normal() const { return normal_; }
    Vec2 felt_tangent() const { return {normal_.y, -normal_.x}; }
    double speed() const { return speed_; }  // m/s, the commanded speed now
    const Person& person() const { return person_; }

private:
    Person person_;
    double dt_;
    std::uint64_t rng_;
    std::vector<drivers::TickRecord> line_;  // the delay line, a ring of delay_s / dt records
    std::size_t head_ = 0, filled_ = 0;
    Vec2 plan_;            // m, the intended position without the press's noise
    double phi_ = 0.0;     // rad, the intended angle
    Vec2 normal_{0.0, 1.0};
    bool felt_contact_ = false;
    double felt_force_ = 0.0;  // N
    double speed_ = 0.0, speed_goal_ = 0.0;  // m/s
    double turn_ = 0.0;  // rad
    bool follow_ = false;
    double lead_ = 0.0, phi_goal_ = 0.0;  // rad
    double approach_ = 0.0;               // m/s
    bool guard_ = true;
    double gain_ = 0.0;                   // m/(s N), the press loop's integral gain
    // Per-tick constants of the motor noise's low-pass and the speed's lag (dimensionless).
    double noise_a_ = 0.0, noise_b_ = 0.0, speed_follow_ = 0.0;
    double noise_speed_ = 0.0, noise_force_ = 0.0;  // unit-variance low-pass noises
    bool drifting_ = false;
    double drift_ = 0.0;        // rad, the angle's unfelt drift so far
    std::uint64_t drift_rng_;   // its noise
};

}  // namespace contactlab::experiments
