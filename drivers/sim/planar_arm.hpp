// planar_arm.hpp — simulated 2-link planar force arm (seed 000 used a Phantom in a vertical
// plane): joint inertias plus the thimble/finger mass at the endpoint, viscous joint damping,
// Coulomb joint friction, motor torque saturation, J^T force rendering and quantised encoders.
//
// Simplification (said once here): the arm's endpoint is the finger centre x_f. On the real device
// the endpoint is the top of the contact element and x_f follows from it and the wire angle psi
// (seed 000 Fig. 8) by a fixed rigid offset, which changes nothing the servo sees.
// Gravity is taken as compensated (the Phantom is counter-balanced).
#pragma once

#include "haptics/vec2.hpp"

namespace contactlab::drivers::sim {

struct PlanarArmParams {
    Vec2 base{0.0, -0.25};          // m, shoulder joint position in the world
    double l1 = 0.20;               // m, upper arm
    double l2 = 0.20;               // m, forearm
    double inertia1 = 4e-3;         // kg m^2, shoulder link + motor rotor (reflected)
    double inertia2 = 2e-3;         // kg m^2, elbow link + rotor
    double endpoint_mass = 0.02;    // kg, thimble + contact element + finger segment
    double damping = 0.05;          // N m s/rad, viscous, each joint
    double friction = 2e-3;         // N m, Coulomb, each joint (smoothed below 1e-3 rad/s)
    double max_torque = 0.35;       // N m, continuous motor torque (per-motor saturation)
    int encoder_counts = 65536;     // counts per joint revolution (after the capstan drive)
};

class PlanarArm {
public:
    explicit PlanarArm(const PlanarArmParams& p);

    // Elbow-up inverse kinematics; returns false when x is out of reach (state unchanged).
    bool place_at(Vec2 x);
    // Forward kinematics of joint angles (rad) and of the true state.
    Vec2 endpoint_of(double q1, double q2) const;
    Vec2 endpoint() const { return endpoint_from(s1_, c1_, s12_, c12_); }
    Vec2 velocity() const {  // m/s, true endpoint velocity
        double J[2][2];
        jacobian_now(J);
        return velocity_from(J);
    }
    double q1() const { return q1_; }  // rad, the true shoulder angle
    double q2() const { return q2_; }  // rad, the true elbow angle (relative)
    // Endpoint from the quantised encoder angles (what the device reports).
    Vec2 measured_endpoint() const;

    // Force (N) the motors should put on the endpoint: tau = J^T F, each torque saturated.
    void command_force(Vec2 f);
    void zero_torque() { tau1_ = tau2_ = 0.0; }
    // Integrates over h (s) with an external force (N) on the endpoint (the hand).
    void step(double h, Vec2 external) {
        double J[2][2];
        jacobian_now(J);
        step_from(h, external, J);
    }
    // The same with the external force a function of the endpoint's position and velocity (m,
    // m/s) at the start of the step, `external(x, v)` (a hand holding the finger): the Jacobian
    // the velocity needs is the one the step needs, made once. The same bits as
    // step(h, external(endpoint(), velocity())).
    template <typename External>
    void step_held(double h, External&& external) {
        double J[2][2];
        jacobian_now(J);
        step_from(h, external(endpoint(), velocity_from(J)), J);
    }

    // The rendered endpoint force the saturated torques actually produce (N).
    Vec2 applied_force() const;
    // Effective Cartesian damping along unit direction n (N s/m): n^T J^-T B J^-1 n.
    double cartesian_damping(Vec2 n) const;
    // Smallest eigenvalue of the Cartesian damping matrix over a grid of reachable points in
    // `lo..hi` (m): what the device declares as its damping.
    double min_cartesian_damping(Vec2 lo, Vec2 hi) const;
    const PlanarArmParams& params() const { return p_; }

private:
    // J (m per rad) and the endpoint (m) from sines and cosines of q1 and q1 + q2: the one
    // formula for the true state, the measured angles and any others.
    void jacobian_from(double s1, double c1, double s12, double c12, double J[2][2]) const {
        J[0][0] = -p_.l1 * s1 - p_.l2 * s12;
        J[0][1] = -p_.l2 * s12;
        J[1][0] = p_.l1 * c1 + p_.l2 * c12;
        J[1][1] = p_.l2 * c12;
    }
    Vec2 endpoint_from(double s1, double c1, double s12, double c12) const {
        return p_.base + Vec2{p_.l1 * c1 + p_.l2 * c12, p_.l1 * s1 + p_.l2 * s12};
    }
    void jacobian_now(double J[2][2]) const { jacobian_from(s1_, c1_, s12_, c12_, J); }  // at the true state, from the stored sines
    Vec2 velocity_from(const double J[2][2]) const { return {J[0][0] * w1_ + J[0][1] * w2_, J[1][0] * w1_ + J[1][1] * w2_}; }
    // step()'s integration, J being the Jacobian at the true state (jacobian_now).
    void step_from(double h, Vec2 external, const double J[2][2]);
    void update_trig();                       // after q1_ or q2_ changed
    void turn_trig(double d1, double d12);    // after a substep turned q1_ by d1, q1_ + q2_ by d12 (rad)
    // sin and cos of the measured (quantised) q1 and q1 + q2, for the encoders' endpoint and the
    // controller's Jacobian: kept while the counts stay the same (a slow or held arm), which
    // skips the library calls with the same bits.
    struct MeasuredTrig {
        double q1 = 0.0, q2 = 0.0;  // rad, quantised
        double s1 = 0.0, c1 = 1.0, s12 = 0.0, c12 = 1.0;
        bool valid = false;
    };
    const MeasuredTrig& measured_trig() const;
    // sin and cos (s, c) of q (rad), the angle of k counts (k a whole number, q = k step as the
    // encoders quantise it): from the table of one turn's counts where it holds q, else computed.
    void count_trig(double k, double q, double& s, double& c) const;

    PlanarArmParams p_;
    double q1_ = 0.0, q2_ = 0.0;    // rad: shoulder absolute, elbow relative
    double w1_ = 0.0, w2_ = 0.0;    // rad/s
    double tau1_ = 0.0, tau2_ = 0.0;  // N m, motor torques held over the servo period
    // sin and cos of q1_ and of q1_ + q2_, kept with the angles: each substep asked for them four
    // times (endpoint, velocity, the Jacobian and J-dot in step), a seventh of a simulated trial's
    // time. A substep turns them by its small increments (turn_trig) instead of calling sincos
    // twice, and every kTrigRefresh-th substep takes them from the library again.
    double s1_ = 0.0, c1_ = 1.0, s12_ = 0.0, c12_ = 1.0;
    int turns_since_refresh_ = 0;
    mutable MeasuredTrig measured_;
    // sin and cos of 1 ... counts - 1 counts, interleaved, made once a process (count_trig); null
    // for an encoder of another resolution than the table's.
    const double* turn_table_ = nullptr;
};

}  // namespace contactlab::drivers::sim
