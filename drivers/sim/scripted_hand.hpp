// scripted_hand.hpp — a human finger as an impedance pulling the device toward a scripted path.
//
// The hand is a spring-damper (stiffness, damping) from the path's intended position to the
// finger; the finger's mass rides on the device endpoint (PlanarArmParams::endpoint_mass). The
// finger angle is driven by the hand (the device cannot push it back, DESIGN.md): it follows the
// path's phi through a first-order lag.
#pragma once

#include "drivers/hand_path.hpp"

#include <cmath>

namespace contactlab::drivers::sim {

struct HandParams {
    double stiffness = 300.0;   // N/m, finger + wrist (human fingertip impedance, light grip)
    double damping = 2.0;       // N s/m
    double phi_lag = 0.02;      // s, time constant of the finger angle following the path
};

class ScriptedHand {
public:
    ScriptedHand(const HandParams& p, HandPath path) : p_(p), path_(std::move(path)) {}
    // Force (N) on the finger at time t (s) with finger position x (m) and velocity v (m/s).
    Vec2 force(double t, Vec2 x, Vec2 v) const noexcept { return pull(path_.at(t), x, v); }
    // The same, `span` an interval of the path (HandPath::interval_at) asked first: the same bits.
    Vec2 force(double t, Vec2 x, Vec2 v, const HandPath::Interval& span) const noexcept {
        return pull(span.holds(t) ? span.at(t) : path_.at(t), x, v);
    }
    // Advances the finger angle over h (s) toward the path's angle at time t (s).
    void step_phi(double t, double h) noexcept { turn_toward(path_.phi_at(t), h); }
    // The same, `span` asked first (as force()).
    void step_phi(double t, double h, const HandPath::Interval& span) noexcept {
        turn_toward(span.holds(t) ? span.phi_at(t) : path_.phi_at(t), h);
    }
    void reset(double t) noexcept { phi_ = path_.phi_at(t); }
    // A hand steering by feel: a new path before the device opens (its first sample is where the
    // finger starts), then one sample ahead every servo tick (HandPath::append).
    void set_path(HandPath path) { path_ = std::move(path); }
    void steer(const PathSample& next) { path_.append(next); }
    double phi() const noexcept { return phi_; }
    const HandPath& path() const noexcept { return path_; }
    const HandParams& params() const noexcept { return p_; }

private:
    Vec2 pull(const PathPoint& q, Vec2 x, Vec2 v) const noexcept { return p_.stiffness * (q.x - x) + p_.damping * (q.v - v); }
    // The angle's first-order lag over h (s) toward `goal` (rad).
    void turn_toward(double goal, double h) noexcept {
        if (h != gain_h_) {  // the substep is nearly always the last one: keep its gain (same bits)
            gain_h_ = h;
            gain_ = 1.0 - std::exp(-h / p_.phi_lag);
        }
        phi_ += (goal - phi_) * gain_;
    }

    HandParams p_;
    HandPath path_;
    double phi_ = 0.0;  // rad
    double gain_h_ = -1.0, gain_ = 0.0;  // s, and 1 - exp(-gain_h_ / phi_lag) for it
};

}  // namespace contactlab::drivers::sim
