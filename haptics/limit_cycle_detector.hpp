// limit_cycle_detector.hpp — reports a sampled contact spring that has become a sustained force
// oscillation (a limit cycle), which the passivity observer (haptics/safety.hpp) cannot see.
//
// Why a second detector. Past the discrete bound K > 2 b / T the sampled spring's zero-order hold
// adds negative damping K T / 2 (N s/m) that out-does the device's b, so no contact can settle.
// Where the spring's linear range (max_force / K, m) spans many encoder counts the oscillation
// grows through that range and the energy sums see it. At high rates and stiffness the linear
// range is one count or less (1.5 N / 55 kN/m = 27 um at 4 kHz x 4 bound, one count of the
// simulated arm is ~18 um): the sensed spring is a relay that flips between free flight and
// (nearly) the clamp, and the loop settles into a bounded bounce whose energy balances over a
// cycle. The measured displacement is one count per several ticks there, so any energy estimate
// from it (b |dx|^2 / T for the damping, F . dx for the work) is off by as much as the cycle's
// whole energy balance (tens of uJ): an energy test cannot resolve it, in either direction.
//
// What stays unambiguous is the force the servo itself commands: a swing of a large fraction of
// the clamp (N), back and forth, faster than any hand moves (a finger taps at <= ~7 Hz; tremor is
// 8-12 Hz; the scripted hand's 300 N/m on the ~0.1 kg rig resonates near 9 Hz), cycle after
// cycle without dying out. The detector counts such half-cycles (extremes separated by at least
// `swing` newtons, hysteresis so quantisation chatter smaller than that never counts) and reports
// once `cycles` full cycles follow each other, each half no longer than 1 / (2 min_frequency) s
// and none smaller than `decay_ratio` of the run's largest swing (a ring-down is not sustained:
// a loop inside the bound loses a fixed fraction of its swing every cycle, a limit cycle none).
//
// It is armed only where the loop is active by the same model: K T / 2 > b with the device's
// declared (lowest) damping b. Below that bound a spring on a sampled, quantised encoder can still
// dither between two counts (K times one count of force, 0.5-1 N at 20 kHz) — a quantisation
// limit cycle, bounded, which Colgate and Schenkel show needs Coulomb friction >= K delta / 2 to
// avoid; it looks exactly like the relay bounce above the bound, and it is not an instability of
// the sampled spring, so it is not reported as one.
//
// O(1) per tick, no allocation, no state beyond a few numbers: safe in the servo tick.
#pragma once

#include <cstdint>

namespace contactlab {

struct LimitCycleParams {
    bool enabled = true;          // false: counts, never reports (e.g. to see the sampling alone)
    // Least peak-to-peak force change counted as a half-cycle, as a fraction of the force clamp
    // in effect (0.3 x 1.5 N = 0.45 N: a buzz nobody would call contact).
    double swing_fraction = 0.3;
    double min_frequency = 20.0;  // Hz: slower oscillations are left to the hand (and the user)
    int cycles = 8;               // full cycles in a row before a report
    // A half-cycle whose swing falls below this fraction of the run's largest restarts the count:
    // the oscillation is dying out, not sustained. 0.8 over the 16 half-cycles of a run lets a ring
    // through only if it decays by less than 20 % in 8 cycles (e.g. a 40 Hz ring of a loop within
    // ~15 % of the bound, b / m ~ 11 /s), and never holds back a limit cycle (constant swing).
    double decay_ratio = 0.95;
};

class LimitCycleDetector {
public:
    void set_params(const LimitCycleParams& p) noexcept { p_ = p; }
    const LimitCycleParams& params() const noexcept { return p_; }
    void reset() noexcept;

    // One tick at time t (s): force magnitude f (N) commanded now, under the clamp max_force (N);
    // `armed`: the loop is past the discrete passivity bound (K T / 2 > b). Returns true once a
    // sustained cycle is seen while armed (it counts unarmed too, so a report comes as soon as
    // the bound is crossed by an edit of K).
    bool step(double t, double f, double max_force, bool armed) noexcept;

    int half_cycles() const noexcept { return half_cycles_; }  // in the current run
    double last_half_period() const noexcept { return last_half_; }  // s

private:
    LimitCycleParams p_;
    double hi_ = 0.0, lo_ = 0.0; // N: running maximum and minimum since the last turn
    double last_turn_t_ = 0.0;   // s: when the last half-cycle was confirmed
    double last_half_ = 0.0;     // s
    double last_extreme_ = 0.0;  // N: the previous turn's extreme
    double run_swing_ = 0.0;     // N: largest half-cycle swing of the current run
    bool have_extreme_ = false;
    int rising_ = 0;             // +1 rising toward a maximum, -1 falling, 0 not yet known
    int half_cycles_ = 0;
    bool primed_ = false;
};

}  // namespace contactlab
