// passivity_controller.hpp — keeps the force on where the loop can be kept passive: an adaptive
// damper that dissipates exactly the energy the passivity observer saw the loop generate
// (Hannaford & Ryu 2002's passivity controller for an impedance display).
//
// The observer (haptics/safety.hpp) sums what the loop generated, W (J). With W > 0 the
// controller adds, for the next period, a damper along the spring's line of action n:
//     f_pc = -alpha v_n n,   alpha = W / (v_n^2 T)   (N s/m),   v_n = n . dx / T (m/s)
// which, if the finger keeps its velocity over the period, dissipates alpha v_n^2 T = W: the
// excess, no more. Its work is in the next tick's F . dx, so the observer sees the dissipation it
// really achieved, not the one hoped for. alpha is capped by what the device can render as a
// sampled damper (`max_damping`): past about m / T (m the device's effective mass, kg) a
// backward-difference damper itself rings at the servo's Nyquist rate. When the cap holds alpha
// below what W asks, the controller says so (`saturated`) and the observer's sum keeps growing:
// the servo faults as without a controller, once the sum passes its threshold.
//
// What it costs: the added damping is felt. It acts only while the loop is generating energy (W >
// 0), in contact, along the spring's line: sliding along a surface is not damped, pressing into it
// is. The servo arms it only past the sampled spring's bound (K T / 2 > b): inside it W still
// makes small positive excursions (the encoders' one-count steps, the hand), and a damper driven
// by one-count velocity steps only excites them. drivers/ caps alpha at min(b, m / T): the
// controller at most doubles the device's damping.
//
// O(1), no allocation: safe in the servo tick.
#pragma once

#include "haptics/vec2.hpp"

#include <cstdint>

namespace contactlab {

// How the servo answers a loop that generates energy.
enum class PassivityMode : std::uint8_t {
    fault,    // the observer reports an instability, the force goes to zero and ramps back
    control,  // the passivity controller damps the excess; a fault only if it cannot
};
const char* to_string(PassivityMode m) noexcept;

class PassivityController {
public:
    void reset() noexcept {
        damping_ = 0.0;
        saturated_ = false;
    }
    // One tick. observed: the observer's sum after this tick (J); dx: the finger's motion this
    // tick (m); line: the spring's line of action (unit, or zero before any force); dt: period (s);
    // max_damping: the cap on alpha (N s/m). Returns the force (N) to add to this tick's command.
    Vec2 step(double observed, Vec2 dx, Vec2 line, double dt, double max_damping) noexcept;
    double damping() const noexcept { return damping_; }   // alpha this tick, N s/m
    bool saturated() const noexcept { return saturated_; } // alpha was capped this tick

private:
    double damping_ = 0.0;
    bool saturated_ = false;
};

}  // namespace contactlab
