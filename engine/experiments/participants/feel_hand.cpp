// feel_hand.cpp — the hand's loop on what it feels (feel_hand.hpp).
#include "engine/experiments/participants/feel_hand.hpp"

#include "engine/experiments/base/random_stream.hpp"
#include "haptics/vec2.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::experiments {
namespace {

// The hand's stiffness in series with a rendered surface (N/m): 300 N/m of the rig's hand
// (drivers/sim/scripted_hand.hpp) with seed 000's 1000 N/m or seed 002's 1300: 231-244. What the
// press loop's gain is tuned against, as a person's is by practice.
constexpr double kSeriesStiffness = 240.0;
// The press loop's gain times the delay times that stiffness (rad of the delayed integrator's
// phase margin used: pi / 2 is the limit; 0.4 settles in about 2.5 delays without overshoot).
constexpr double kLoopGain = 0.4;
constexpr double kNoiseTau = 0.05;   // s, the low-pass of the motor noise
constexpr double kSpeedTau = 0.15;   // s, how fast the speed follows its command
constexpr double kTouch = 0.02;      // N: a force below this is not felt as contact
// A guarded slide (FeelHand::set_guarded): it stops advancing at the person's hold_back times the
// target force (HandPopulation), and never means the finger to be more than kMaxStretch
// target-force stretches (F* / the series stiffness) deeper than the arm feels it (this model's
// choice).
constexpr double kMaxStretch = 2.0;

// An Ornstein-Uhlenbeck step of unit stationary variance: `a` = exp(-dt / kNoiseTau) and `b` =
// sqrt(1 - a^2), the same every tick (made once, in the constructor).
double ou(double x, double a, double b, std::uint64_t& rng) { return a * x + b * normal01(rng); }

// The finger angle that puts the pad's middle on a contact whose normal (toward the finger's
// centre) is n: the pad's middle lies at phi - pi/2 from the centre (DESIGN.md).
double angle_facing(Vec2 n) {
    double phi = std::atan2(-n.y, -n.x) + 0.5 * kPi;
    if (phi > kPi) phi -= 2.0 * kPi;
    return phi;
}

}  // namespace

FeelHand::FeelHand(const Person& person, drivers::PathSample start, double dt, std::uint64_t noise_seed)
    : person_(person), dt_(dt), rng_(mix64(noise_seed ^ 0x4A4Dull)), plan_(start.x), phi_(start.phi),
      phi_goal_(start.phi), drift_rng_(mix64(noise_seed ^ 0xD81F7ull)) {
    const std::size_t n = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(person_.delay_s / dt_)));
    line_.resize(n);
    gain_ = kLoopGain / (person_.delay_s * kSeriesStiffness);
    noise_a_ = std::exp(-dt_ / kNoiseTau);
    noise_b_ = std::sqrt(1.0 - noise_a_ * noise_a_);
    speed_follow_ = 1.0 - std::exp(-dt_ / kSpeedTau);
}

drivers::PathSample FeelHand::step(const drivers::TickRecord& now) {
    // The delay line: what was displayed delay_s ago reaches the hand now. Of it the hand reads
    // the force, the contact and the finger's place, taken before `now` takes its slot.
    const drivers::TickRecord& old = line_[head_];
    const Vec2 felt_finger = old.finger;
    const bool have = filled_ >= line_.size();
    if (have) {
        const double f = std::hypot(old.force.x, old.force.y);
        felt_contact_ = old.contact && f > kTouch;
        felt_force_ = felt_contact_ ? f : 0.0;
        if (felt_contact_) normal_ = old.force / f;
    }
    line_[head_] = now;
    head_ = (head_ + 1) % line_.size();
    filled_ = std::min(filled_ + 1, line_.size());
    // Speed: toward the command, with signal-dependent noise.
    speed_ += (speed_goal_ - speed_) * speed_follow_;
    noise_speed_ = ou(noise_speed_, noise_a_, noise_b_, rng_);
    noise_force_ = ou(noise_force_, noise_a_, noise_b_, rng_);
    // A guarded move: pushing against more than the target force (the surface rose ahead of the
    // finger faster than the felt tangent turned), the hand holds back its advance, fully at
    // hold_back times the target, until the press loop and the felt normal have caught up.
    const double resist = std::clamp((felt_force_ - person_.press_force_n) / ((person_.hold_back - 1.0) * person_.press_force_n), 0.0, 1.0);
    // Out of touch, the hand does not go on along a tangent it no longer feels: it reaches back
    // for the surface along the last felt normal (the press below) and advances again on touch.
    const double go = felt_contact_ ? 1.0 - (guard_ ? resist : 0.0) : 0.0;
    const double v = std::max(0.0, speed_ * go * (1.0 + person_.speed_noise_cv * noise_speed_));
    // The felt tangent turned clockwise by turn_ (toward the surface for travel along +tangent).
    const Vec2 tan = felt_tangent();
    const double ca = std::cos(turn_), sa = std::sin(turn_);
    const Vec2 dir{tan.x * ca + tan.y * sa, -tan.x * sa + tan.y * ca};
    // Press: into the surface along the felt normal at gain (F* - F); before the first touch the
    // strategy's approach speed, when it set one.
    double press = gain_ * (person_.press_force_n - felt_force_);  // m/s into the surface
    if (!felt_contact_ && approach_ > 0.0) press = std::max(press, approach_);
    plan_ += (v * dir - press * normal_) * dt_;
    // The arm knows where the finger is (felt as late as the rest): the hand never means the
    // finger to be deeper into the surface than twice its target force's stretch beyond it, so
    // reaching back for a surface lost, or pressing while the display's force is saturated, does
    // not wind the press up (a person feels their own finger and does not drive it on).
    if (have && guard_) {
        const double depth = glm::dot(felt_finger - plan_, normal_);  // m into the surface, past the finger
        const double most = kMaxStretch * person_.press_force_n / kSeriesStiffness;
        if (depth > most) plan_ += (depth - most) * normal_;
    }
    // The press's own noise: a force of sd force_noise_cv F* through the series stiffness.
    const Vec2 intended = plan_ - normal_ * (person_.force_noise_cv * person_.press_force_n / kSeriesStiffness * noise_force_);
    // The finger's angle: held, or turned with the felt normal and `lead` further round, never
    // past pointing straight down (the wrist's reach in a plane: -pi/2).
    if (follow_) phi_goal_ = std::max(-0.5 * kPi, angle_facing(normal_) - lead_);
    // Unfelt drift, once the strategy lets the angle drift: a random walk (a wrist held by
    // proprioception alone wanders; with the contact location on the pad the person would see it).
    if (drifting_ && person_.angle_drift_rad_sqrt_m > 0.0)
        drift_ += person_.angle_drift_rad_sqrt_m * std::sqrt(v * dt_) * normal01(drift_rng_);
    phi_ = phi_goal_ + drift_;
    // For the end of the device's next advance: the record was read at now.t, the device is at
    // now.t + dt and advances to now.t + 2 dt under this sample.
    return {now.t + 2.0 * dt_, intended, phi_};
}

}  // namespace contactlab::experiments
