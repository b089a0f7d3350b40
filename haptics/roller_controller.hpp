// roller_controller.hpp — the contact-location (roller) position loop of seed 000, eq. 2:
//
//     F_l = (Kp + Ki / s) (l_d - l) - Kd s l
//
// Gains are continuous-time, in physical units (drive per m, per m s, per m/s), and are discretised
// with the period of each tick, so the same gains give the same closed loop at 1 kHz and 10 kHz
// (tests/drivers/test_roller_tracking.cpp compares 1 and 4 kHz); below ~1 kHz, where the design's
// poles would sit near the sampling, they are re-placed at a fraction of it (RollerGains::pole):
//   P: Kp e[k]
//   I: I[k] = I[k-1] + Ki e[k] T             (rectangular rule; the integral is kept in drive units)
//   D: -Kd v_f[k], v_f the measured rate (l[k] - l[k-1]) / T through the first-order low-pass
//      1 / (s / w_c + 1) discretised exactly: v_f += (1 - exp(-w_c T)) (v - v_f), w_c = 2 pi f_c
//   FF: +kff r_f[k], r_f the target's rate (l_d[k] - l_d[k-1]) / T through its own low-pass at
//      ff_cutoff_hz (beyond eq. 2; kff = 0 is eq. 2 alone, see RollerGains::kff)
// Derivative on the *measurement* (a step in l_d never kicks the motor); conditional-integration
// anti-windup, output saturation and travel limits. Gains may change live between ticks: the
// integral is stored in output units, so changing Ki does not step the output.
//
// The output is the motor drive in the device's units (the simulated CLD roller takes volts).
// The defaults are placed for the simulated CLD roller (drivers/sim/cld_roller.hpp), whose small-
// signal plant is l / V = g / (s (tau s + 1)) with g = 1 / (k_e 2 pi / lead) = 0.0223 m/(V s) and
// tau = 16 ms: with the three closed-loop poles at s = -p, p = 400 rad/s (p T = 0.4 at 1 kHz),
//   Kp = 3 tau p^2 / g,  Ki = tau p^3 / g,  Kd = (3 tau p - 1) / g.
#pragma once

namespace contactlab {

struct RollerGains {
    double kp = 3.45e5;         // drive per m of error (V/m)
    double ki = 4.6e7;          // drive per m s of error (V/(m s))
    double kd = 820.0;          // drive per m/s of roller speed (V s/m)
    double d_cutoff_hz = 300.0; // derivative low-pass cut-off (Hz)
    double max_drive = 12.0;    // output saturation, |u| <= max_drive (V)
    // Velocity feed-forward, beyond eq. 2: drive per m/s of the target's rate d l_d/dt (V s/m),
    // the rate low-passed at ff_cutoff_hz. Why: eq. 2 damps the *measured* rate (-Kd s l), so on
    // a target moving at v the loop must hold Kd v + back_emf v of drive from P and I to move at
    // all; the integral stops at the rail (anti-windup, |I| <= max_drive), so at 5 cm/s (44 V of
    // Kd v against a 12 V rail) P holds the rest and the roller lags (Kd v + back_emf v -
    // max_drive) / Kp = 0.10 mm for as long as the target moves. kff = Kd + back_emf (864.88
    // V s/m, the default) supplies exactly that drive: the derivative then acts on the error's
    // rate and the back-EMF is pre-paid, so a steady ramp needs no P or I. 0 is seed 000's pure
    // eq. 2 (the figures for both: docs/simulation.md, "Roller"). Below 1 kHz it is re-placed with Kd.
    double kff = 864.88;
    // Cut-off of the target-rate filter (Hz). l_d moves in encoder steps (0.04 mm of l per angle
    // count, 0.02 mm per arm count) that a per-tick difference turns into +-40 mm/s of rate; at
    // 300 Hz (the derivative's) kff x that is +-30 V of chatter and doubles the slow-motion error.
    // 20 Hz averages the steps over ~8 ms and lags a ramp's onset by 1 / (2 pi 20) = 8 ms, inside
    // the transient the motor's force limit imposes anyway (bench: roller tracking).
    double ff_cutoff_hz = 20.0;
    // Sampling limit of the design (below 1 kHz). The gains above place the three closed-loop
    // poles at s = -pole (rad/s); a discrete PID holds that design only while pole T is well
    // inside the sampling (at p T = 0.8-4, i.e. 500-100 Hz, the same gains limit-cycle by up to
    // 2 mm and track the block task 1.3-2.4x worse). When pole T exceeds max_pole_period the
    // controller re-places the poles at p = max_pole_period / T with the pole-placement scaling
    // (s = p / pole). 0.4 is the defaults' own p T at 1 kHz, so below 1 kHz the loop is the 1 kHz
    // loop slowed by T / 1 ms (at 0.5, 500-800 Hz kept a 17-34 um limit cycle):
    //   Kp s^2, Ki s^3, Kd s - (1 - s) back_emf, kff s
    // (kff scales as Kd + back_emf does, so kff = Kd + back_emf stays the exact cancellation;
    // Kd + back_emf = 3 tau p / g grows with p; back_emf = 1 / g is the damping the motor's own
    // back-EMF gives, V s/m). pole = 0 turns this off (gains used as given at every rate).
    double pole = 400.0;            // rad/s, where kp, ki, kd were placed
    double max_pole_period = 0.4;   // largest p T kept (dimensionless)
    double back_emf = 44.88;        // V s/m, 1 / g of the simulated CLD roller (k_e 2 pi / lead)
};

// The gains the controller uses at period dt (s): `g` itself while g.pole dt <= g.max_pole_period,
// otherwise re-placed at p = max_pole_period / dt (see RollerGains::pole).
RollerGains sampled_roller_gains(const RollerGains& g, double dt) noexcept;

struct RollerTravel {
    double min = -0.010;  // m: travel limits along the pad (seed 000: about 2.0 cm of travel)
    double max = 0.010;   // m
};

// False when a gain is NaN/Inf or negative, or the cut-off or saturation is not positive: the
// controller then outputs zero drive (the leadscrew holds the roller) instead of a wild or
// non-finite one. servo_params_check.hpp says which gain and why, for the user.
bool roller_gains_usable(const RollerGains& g) noexcept;

class RollerController {
public:
    RollerController() = default;
    RollerController(const RollerGains& g, const RollerTravel& travel) : gains_(g), travel_(travel) {}

    void set_gains(const RollerGains& g) noexcept {
        gains_ = g;
        derived_.valid = false;
    }
    const RollerGains& gains() const noexcept { return gains_; }
    void set_travel(const RollerTravel& t) noexcept { travel_ = t; }
    const RollerTravel& travel() const noexcept { return travel_; }

    // Forgets integral and derivative history; the next step starts from measurement l (m).
    void reset(double l) noexcept;

    // One tick: desired location l_d (m), measured location l (m), period dt (s). Returns the
    // saturated drive. Non-finite inputs give 0 and reset the state.
    double step(double l_d, double l, double dt) noexcept;

    double target() const noexcept { return target_; }  // l_d after the travel limits (m)
    double drive() const noexcept { return drive_; }
    bool saturated() const noexcept { return saturated_; }

private:
    // What a tick derives from the gains and its period, kept while both hold: the filters' two
    // exponentials, the gains sampled for dt and their check were a third of the roller's tick in
    // a simulated study (the servo's period does not change from tick to tick).
    struct Derived {
        bool valid = false;
        double dt = 0.0;        // s
        bool usable = false;    // roller_gains_usable(gains_)
        double alpha = 0.0;     // the measured rate's low-pass coefficient at dt
        double alpha_ff = 0.0;  // the target rate's
        RollerGains sampled;    // sampled_roller_gains(gains_, dt)
    };
    const Derived& derived(double dt) noexcept;

    RollerGains gains_;
    RollerTravel travel_;
    Derived derived_;
    double integral_ = 0.0;   // drive units
    double rate_f_ = 0.0;     // filtered dl/dt (m/s)
    double target_rate_f_ = 0.0;  // filtered dl_d/dt (m/s)
    double prev_target_ = 0.0;    // m
    double prev_l_ = 0.0;     // m
    bool primed_ = false;
    double target_ = 0.0;
    double drive_ = 0.0;
    bool saturated_ = false;
};

}  // namespace contactlab
