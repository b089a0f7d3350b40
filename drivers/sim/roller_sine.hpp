// roller_sine.hpp — the CLD roller alone under its position loop, in virtual time: sine response
// and the large-signal bandwidth of seed 000 §4.3 ("1.0 cm sinusoidal commands with a bandwidth of
// approximately 8 Hz").
//
// The rig is the one the servo drives (drivers/sim/cld_roller.hpp: motor, self-locking leadscrew,
// stiction, wires) and the controller is the servo's own (haptics/roller_controller.hpp), stepped
// at the servo period with the drive held between ticks and the roller integrated at sub-steps,
// exactly as SimCldDevice does. Nothing here sleeps: results are deterministic.
#pragma once

#include "drivers/sim/cld_roller.hpp"
#include "haptics/roller_controller.hpp"

#include <vector>

namespace contactlab::drivers::sim {

struct SineTest {
    double rate = 1000.0;         // Hz, servo rate
    double amplitude = 0.005;     // m, sine amplitude about the centre (0.005: 1.0 cm peak to peak)
    int settle_cycles = 4;        // cycles run before measuring (start transient)
    int measure_cycles = 6;       // cycles the fundamental is extracted over
    double substep = 1e-4;        // s, longest integration step of the roller
    int min_substeps = 10;        // sub-steps per servo period at least (as SimCldDevice)
    double travel = 0.0;          // m, total travel the controller may use, centred; 0: all of it
};

struct SineResponse {
    double freq = 0.0;            // Hz
    double gain = 0.0;            // |fundamental of l| / amplitude (l: motor encoder, m/m)
    double phase = 0.0;           // rad, phase of l relative to l_d (negative: lag)
    double element_gain = 0.0;    // the same for the contact element (what the finger feels)
    double max_error = 0.0;       // m, max |l_d - l| over the measured cycles
};

// One frequency (Hz): the roller at rest at the centre tracks l_d = amplitude sin(2 pi f t).
SineResponse roller_sine_response(const RollerParams& plant, const RollerGains& gains, const SineTest& test,
                                  double freq);

struct BandwidthResult {
    double bandwidth = 0.0;              // Hz, first frequency where the gain falls to 1/sqrt(2)
    bool found = false;                  // false: the gain never fell that low below max_freq
    std::vector<SineResponse> sweep;     // the log sweep, then the bisection points, by frequency
};

// Log sweep from min_freq to max_freq (Hz), `per_decade` points a decade, then bisection on the
// first crossing of -3 dB to `tolerance` Hz.
BandwidthResult roller_bandwidth(const RollerParams& plant, const RollerGains& gains, const SineTest& test,
                                 double min_freq = 0.5, double max_freq = 100.0, int per_decade = 12,
                                 double tolerance = 0.01);

// Steps and a sine for the roller alone at `rate` (Hz): holds of `hold` s at +8, -8, +2, 0 mm
// (steps of up to 16 mm saturate the 12 V drive for tens of ms: the anti-windup's test), then
// 1 s of a 5 Hz, 5 mm sine. What a loop must keep at any rate and gains: finite, drive on the
// rail, nut inside the travel; and, stable, settled at the end of each hold.
struct RollerStepRun {
    bool finite = true;
    double max_drive = 0.0;        // V, largest |drive| commanded
    double max_nut = 0.0;          // m, largest |nut position|
    double max_settle_error = 0.0; // m, largest |target - encoder| over the last 20 % of the holds
    double max_sine_error = 0.0;   // m, largest |target - encoder| over the sine's last 0.5 s
    double max_overshoot = 0.0;    // m, furthest past a step's target, in the step's direction
};
RollerStepRun roller_step_run(const RollerParams& plant, const RollerGains& gains, double rate, double hold = 0.4,
                              double substep = 1e-4, int min_substeps = 10);

// The response to a jump of l_d (bench "roller jump"): the roller at rest at `from` (m) under
// `gains` at `rate` (Hz); l_d jumps to `to` (m) and is held for `hold` s.
struct RollerJumpResponse {
    double jump = 0.0;            // m, to - from
    double settle_s = 0.0;        // s from the jump until |l_d - l| stays within `band`; the hold's length if never
    double band = 0.0;            // m, the settling band
    double force_limited_s = 0.0; // s, the least any controller can take (force_limited_jump_time)
    double overshoot = 0.0;       // m, furthest the encoder went past `to`, in the jump's direction
    double max_excursion = 0.0;   // m, furthest |nut| from the travel's centre (inside half_travel: no overshoot beyond the travel)
    double half_travel = 0.0;     // m
    bool finite = true;
};
RollerJumpResponse roller_jump_response(const RollerParams& plant, const RollerGains& gains, double from, double to,
                                        double rate = 1000.0, double band = 0.05e-3, double hold = 0.5,
                                        double substep = 1e-4, int min_substeps = 10);

// The least time (s) the roller can move `jump` (m) from rest to rest with its drive on the rail:
// full drive toward the target, then full drive back, switched so that the nut stops on the target
// (one switch is time-optimal for this second-order plant: Pontryagin's bang-bang). Found by
// bisection on the switch time, on the same roller model (back-EMF, friction, stiction), stepped
// at 10 us. This is the motor's force limit the jump settling is measured against.
double force_limited_jump_time(const RollerParams& plant, double jump);

}  // namespace contactlab::drivers::sim
