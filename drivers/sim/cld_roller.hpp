// cld_roller.hpp — simulated contact-location display actuator (seed 000 §2): a small DC motor on
// the forearm turns a non-backdrivable leadscrew whose nut pushes the contact element along the
// thimble through two sheathed push-pull wires.
//
// Model (nut coordinate x, m): armature current i = (V - k_e N v) / R with N = 2 pi / lead
// (rad/m); drive force k_t N i; reflected mass J_m N^2 + m_nut; Coulomb friction with stiction
// (the nut sticks while the drive is below the break-away force); hard stops at the travel ends.
// The leadscrew is self-locking, so forces on the element never move the nut. The wires are a
// spring-damper between the nut and the element (mass m_e), which is what the finger feels.
// The motor encoder measures the nut (seed 000: "as measured by the motor's encoder").
#pragma once

#include "haptics/vec2.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::drivers::sim {

// Identification (the seeds give the rig's figures, not its parts; each choice says what fixes it):
// - lead 0.7 mm (an M4 x 0.7 screw): lead angle atan(0.7 / (pi 3.5 mm)) = 3.6 deg, below the
//   friction angle of a steel/bronze pair (atan 0.15 = 8.5 deg), so the screw is self-locking
//   (seed 000: non-backdrivable); with a 1024-line encoder (4096 counts) one count is
//   0.7 mm / 4096 = 0.171 um, seed 002's "nominal resolution ... 0.17 um".
// - motor: a small coreless DC motor (10 ohm, 5 mN m/A, rotor 0.4 g cm^2) on a 12 V amplifier.
//   Reflected to the nut: mass J (2 pi / lead)^2 = 3.2 kg, back-EMF damping (k_t 2 pi / lead)^2 / R
//   = 201 N s/m (mechanical time constant 16 ms), stall force 54 N, no-load speed 0.27 m/s. The
//   force limit makes a 1 cm peak-to-peak sine saturate the motor from about 7 Hz on, which is
//   what sets the large-signal bandwidth (seed 000: "approximately 8 Hz"; drivers/sim/roller_sine.hpp).
struct RollerParams {
    double travel = 0.020;         // m, total travel (seed 000: about 2.0 cm; seed 002 limits it to 18 mm in software)
    double lead = 0.0007;          // m per motor revolution
    double resistance = 10.0;      // ohm
    double torque_constant = 0.005;  // N m/A (= back-EMF constant, V s/rad)
    double rotor_inertia = 4e-8;   // kg m^2
    double nut_mass = 0.005;       // kg
    double coulomb = 1.0;          // N, sliding friction at the nut (leadscrew + wires in their sheaths)
    double stiction = 1.5;         // N, break-away force
    double viscous = 0.5;          // N s/m, at the nut
    double wire_stiffness = 5000;  // N/m, push-pull wires
    double wire_damping = 0.5;     // N s/m
    double element_mass = 0.003;   // kg, contact cylinder + carriage
    int encoder_counts = 4096;     // per motor revolution (1024 lines x 4): lead/4096 = 0.171 um
    double max_voltage = 12.0;     // V, amplifier rail
};

class CldRoller {
public:
    explicit CldRoller(const RollerParams& p)
        : p_(p), n_(kTwoPi / p.lead), mass_(p.rotor_inertia * n_ * n_ + p.nut_mass) {}
    void place_at(double l);                 // nut and element at l (m), at rest
    void set_voltage(double v);              // V, clamped to the rail
    // Integrates h seconds (inline: every 0.1 ms substep of a simulated trial calls it).
    void step(double h) {
        const double n = n_;  // rad of motor per m of nut travel
        const double mass = mass_;
        const double current = (volts_ - p_.torque_constant * n * v_) / p_.resistance;
        const double drive = p_.torque_constant * n * current - p_.viscous * v_;  // N
        // Stiction: a resting nut stays put until the drive exceeds the break-away force.
        if (stuck_) {
            if (std::abs(drive) > p_.stiction) stuck_ = false;
        }
        if (!stuck_) {
            const double sign = v_ != 0.0 ? (v_ > 0.0 ? 1.0 : -1.0) : (drive > 0.0 ? 1.0 : -1.0);
            const double v_new = v_ + h * (drive - p_.coulomb * sign) / mass;
            // Velocity reversal through zero with too little drive: the nut sticks.
            if (v_ != 0.0 && v_new * v_ <= 0.0 && std::abs(drive) <= p_.stiction) {
                v_ = 0.0;
                stuck_ = true;
            } else {
                v_ = v_new;
            }
        }
        x_ += v_ * h;
        const double half = half_travel();
        if (x_ > half || x_ < -half) {  // hard stop: inelastic
            x_ = std::clamp(x_, -half, half);
            v_ = 0.0;
            stuck_ = true;
        }
        // Element on the wires: spring-damper to the nut. Semi-implicit Euler.
        const double fw = p_.wire_stiffness * (x_ - xe_) + p_.wire_damping * (v_ - ve_);
        ve_ += h * fw / p_.element_mass;
        xe_ += ve_ * h;
    }
    double nut() const { return x_; }        // m
    double element() const { return xe_; }   // m, what the finger feels
    double measured() const;                 // m, quantised encoder reading of the nut
    double half_travel() const { return 0.5 * p_.travel; }
    bool stuck() const { return stuck_; }
    const RollerParams& params() const { return p_; }

private:
    RollerParams p_;
    // Fixed by the parameters, so made once (a division each 0.1 ms substep, otherwise):
    double n_;     // rad of motor per m of nut travel
    double mass_;  // kg, the rotor's inertia reflected through the screw, plus the nut
    double x_ = 0.0, v_ = 0.0;    // nut, m and m/s
    double xe_ = 0.0, ve_ = 0.0;  // element
    double volts_ = 0.0;
    bool stuck_ = true;
};

}  // namespace contactlab::drivers::sim
