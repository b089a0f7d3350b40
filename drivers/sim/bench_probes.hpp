// bench_probes.hpp — closed-loop measurements on the simulated CLD rig, as library functions, so
// `contactlab bench` (issue 8 §1: "Rate vs stiffness", "Roller tracking error vs PID gains and
// finger speed") and the drivers tests (issue 4 §5) run one implementation and print the same
// numbers. Everything runs in virtual time (drivers/sim/sim_rig.hpp, drivers/sim/roller_sine.hpp):
// deterministic, no sleeping, as fast as the CPU allows; results do not depend on machine load,
// only the time taken does.
//
// Two layers: the tables (namespace contactlab, the interface the bench calls) and the single
// measurements they are built from (namespace contactlab::drivers::sim, which the tests also use
// for their assertions). All quantities SI unless a name says otherwise.
#pragma once

#include "drivers/sim/cld_roller.hpp"
#include "drivers/sim/planar_arm.hpp"
#include "drivers/sim/sim_cld_device.hpp"
#include "haptics/roller_controller.hpp"
#include "haptics/servo_tick.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace contactlab {

// ---- Rate vs stiffness ------------------------------------------------------------------------
// The hand presses the finger 2 mm into a floor (no hand damping, so the arm's own damping b is
// all the loop has) and the spring's K is bisected for the largest value that still holds. The
// sampled spring on a damped mass is passive for K < 2 b / T (Colgate and Schenkel), b the arm's
// damping along the contact normal and T the servo period: `passivity_bound`. The servo itself
// only knows the device's declared damping, the lowest over its workspace (`bound_declared`, about
// 2/3 of the normal's here): its limit-cycle detector arms above that.
//
// What a loop past the bound does, at each of `kAboveBoundRatios` x passivity_bound, pressed and
// held (drivers/sim/stability_probes.hpp, 3 s):
enum class AboveBoundOutcome : std::uint8_t {
    detected,        // ServoFault::instability reported, output zeroed
    bounded_bounce,  // not reported; oscillating (force ripple >= 0.1 N) but bounded at the clamp
    at_rest,         // not reported; no oscillation (ripple < 0.1 N)
    runaway,         // not reported and not bounded (NaN, force over the clamp, or >= 1 m/s)
};
const char* to_string(AboveBoundOutcome o) noexcept;
inline constexpr double kAboveBoundRatios[4] = {1.5, 4.0, 20.0, 1000.0};
struct AboveBoundProbe {
    double ratio = 0;            // K / passivity_bound
    AboveBoundOutcome outcome = AboveBoundOutcome::runaway;
    double detect_time = -1;     // s from first contact to the report (detected only)
    InstabilityCause cause = InstabilityCause::none;  // which detector (detected only)
    double max_force = 0;        // N, largest commanded
};

struct StabilityRow {
    double rate_hz = 0;          // servo rate
    double passivity_bound = 0;  // 2 b / T, N/m, b along the press's normal
    double k_no_fault = 0;       // largest K (N/m) with no fault reported, real (simulated) arm
    double k_settles = 0;        // largest K (N/m) that settles, real arm
    double k_ideal_settles = 0;  // the same with ideal encoders and no joint friction
    // Beyond the bench's first interface:
    double k_ideal_no_fault = 0; // N/m, largest K with no fault reported, ideal arm
    double b_normal = 0;         // N s/m, the arm's damping along the floor normal at the press point
    double b_declared = 0;       // N s/m, what the device declares (its lowest)
    double bound_declared = 0;   // N/m, 2 b_declared / T: the bound the servo knows
    double search_lo = 0;        // N/m, bisection bracket: K values are clipped to [search_lo,
    double search_hi = 0;        //   search_hi]; a K equal to search_hi means "held even there"
    double resolution = 0;       // ratio the bisection stops at (hi / lo), e.g. 1.02: 2 %
    AboveBoundProbe above[4];    // at kAboveBoundRatios x passivity_bound
};
// quick: 250 and 1000 Hz (the same rows as full's); full: 100, 250, 1000, 4000, 10000, 20000 Hz.
// Bisection on log K to 2 %, bracket [0.05, 4] x passivity_bound at every rate.
std::vector<StabilityRow> stability_table(bool quick);

// ---- Z-width: largest stable K against the virtual damping B ----------------------------------
// The stable region of the rig over the scene's stiffness K (N/m) and normal damping B (N s/m,
// `force.damping`). The proxy (haptics/proxy.cpp) adds B (d_k - d_{k-1}) / dt along the contact
// normal while in contact, d the depth under the sampled (encoder) finger position: a backward-
// difference damper, as Colgate and Schenkel model it, but one-sided (it may cancel the spring's
// push, never pull) and with dt = the proxy's default 1 ms whatever the rate, because the servo
// tick does not pass its period: at rate R the damping applied is B x 1000 / R (`damping_applied`,
// measured by damper_response(), so the rows follow if that changes).
//
// Theory, b the device's damping, T the period, B_a the damping applied: the loop is passive iff
// b > K T / 2 + |B_a| (Colgate and Schenkel), K_max = 2 (b - |B_a|) / T, 0 from |B_a| = b; drawn
// with b along the press's normal (`bound_normal`) and the declared b (`bound_declared`). Passivity
// is sufficient, not necessary: to first order in T the held spring adds K T / 2 of negative
// damping and the delayed damper B_a of positive, so the loop is *stable* up to 2 (b + B_a) / T
// (Gil, Avello, Rubio and Florez 2004): the no-fault K at 1 kHz follows that. From 4 kHz up the
// no-fault K sits at the declared 2 b / T, where the limit-cycle detector arms (its arming does
// not count B) and reports the encoders' quantisation limit cycle.
//
// For each (rate, B) K is bisected (as in the stability table: on log K, bracket [0.05, 4] x
// 2 b_normal / T, to `resolution`) in two contacts of drivers/sim/stability_probes.hpp, 1 s each,
// no hand damping: `press` (2 mm into a floor and held) and `slide` (pressed 2 mm, then a 6 cm
// stroke along the floor, up to 0.19 m/s). K holds with *no fault* when the device opened, every
// force and position stayed finite, the finger under 1 m/s (no runaway) and the servo raised no
// fault (its instability detectors: passivity observer and limit-cycle detector). It is *stable*
// when it also settled: pressed, the commanded |F|'s peak-to-peak over the run's last quarter
// below 0.1 N or below 0.9 x that over the quarter before (the stability table's "settles", so at
// B = 0 k_press is its k_settles); sliding, the force follows the stroke, so the peak-to-peak of
// |F| less its 20 ms centred mean over the last quarter below 0.1 N. The 0.1 N is also what the
// encoders' counts (~18 um) put into the force through K and, as velocity steps of a count per
// damper dt, through B: past B ~ 0.5 N s/m the settled K falls by 2 / dt per N s/m.
struct ZWidthRow {
    double rate_hz = 0;          // servo rate
    double damping = 0;          // B, N s/m: the scene's force.damping
    double damping_applied = 0;  // B_a, N s/m: the servo's force per m/s of sampled normal velocity
    double k_press = 0;          // N/m, largest stable K pressed (search_hi: held even there;
    double k_slide = 0;          //   0: not even search_lo), and sliding
    double k_press_no_fault = 0; // N/m, largest K with no fault (settling not asked), pressed
    double k_slide_no_fault = 0; //   and sliding
    double b_normal = 0;         // N s/m, the arm's damping along the floor normal at the press point
    double b_declared = 0;       // N s/m, what the device declares (its lowest over the press's box)
    double bound_normal = 0;     // N/m, 2 (b_normal - |B_a|) / T; <= 0: no K is passive
    double bound_declared = 0;   // N/m, 2 (b_declared - |B_a|) / T
    double search_lo = 0;        // N/m, bisection bracket
    double search_hi = 0;
    double resolution = 0;       // ratio the bisection stops at (hi / lo)
};
// Rows per rate (1 kHz, then 10 kHz), B ascending. Full: B in {0, 0.25, 0.5, 0.75, 1, 1.5, 2, 3,
// 5} N s/m at both rates; quick: {0, 0.5, 1, 2, 5} at 1 kHz and {0, 1, 2} at 10 kHz. 2 % bisection.
std::vector<ZWidthRow> zwidth_table(bool quick);

// ---- Roller tracking error vs PID gains and finger speed -------------------------------------
// Seed 000's block task (drivers/tasks.hpp: along the top, over the corner, down the far face) on
// the simulated CLD at `rate_hz`; the error is the roller's encoder against the servo's target
// l_d, sampled every tick while engaged and in contact.
//
// Tracking vs jumps. Seeds 000/001 give the error "during hand motion" (0.05 mm at 5 cm/s, 0.01 mm
// slow); the block task also has moments where l_d's motion changes faster than a force-limited
// roller can follow: past the block's edge the contact starts along the pad at the hand's speed
// from rest (a step in d l_d/dt), it stops when the finger tips, and contact is made and lost.
// A tick is a *jump* of l_d when l_d's mean rate over the next kJumpRateWindow differs from that
// over the previous one by more than kJumpRateChange (this also catches any step of l_d of more
// than kJumpRateChange x kJumpRateWindow = 0.2 mm), or when contact is missing within
// kJumpRateWindow of it. `max_tracking_error` is the error outside the jumps and the
// kJumpSettleWindow after each; `max_jump_error` the error inside them.
inline constexpr double kJumpRateWindow = 0.010;  // s: averages out the encoders' steps of l_d
                                                  //   (0.04 mm per angle count: <= 8 mm/s of noise between two windows)
inline constexpr double kJumpRateChange = 0.020;  // m/s: above that noise; below it the onset
                                                  //   floor (onset_floor()) is under 0.04 mm at 1 kHz
inline constexpr double kJumpSettleWindow = 0.030;  // s: a 5 cm/s onset takes 3 ms of full force
                                                    //   and the 400 rad/s triple pole ~20 ms to settle
struct RollerTrackingRow {
    double gain_scale = 1;       // multiplier on the default closed-loop bandwidth (pole placement) or gains
    double finger_speed = 0;     // m/s along the block task's contour
    double rate_hz = 1000;
    bool feed_forward = true;    // velocity feed-forward (RollerGains::kff = Kd + back-EMF); false: seed 000's pure eq. 2
    double max_error = 0;        // m, roller vs target, every tick in contact (tracking and jumps)
    double rms_error = 0;        // m
    double max_tracking_error = 0;  // m, outside the jumps' windows (see above)
    double rms_tracking_error = 0;  // m
    double max_jump_error = 0;   // m, inside them
    int jumps = 0;               // jumps of l_d found
    // What the finger feels, over the same tracking ticks: the contact element (after the wires)
    // against the *true* contact location, l_d from the simulated finger's unquantised pose through
    // the same proxy code. The target above is computed from the encoders (finger angle: R 2 pi /
    // 4096 = 0.040 mm of l per count; arm: ~0.02 mm of finger position per joint count), a
    // staircase no continuous roller can follow to better than half its step.
    double max_true_tracking_error = 0;  // m, |l_d true - l_element|
    double rms_true_tracking_error = 0;  // m
    double max_target_staircase = 0;     // m, |l_d (encoders) - l_d true|: the quantisation alone
    double max_true_encoder_error = 0;   // m, |l_d true - l_encoder|: the nut, as seed 000 measured it
    // Beyond the bench's interface:
    double pole_rad_s = 0;       // rad/s, the placed closed-loop pole (triple), 400 x gain_scale
    double max_element_error = 0;  // m, contact element (after the wires: what the finger feels) vs target
    double target_range = 0;     // m, how far l_d travelled (the task must move the roller)
    double max_target_rate = 0;  // m/s, fastest l_d over 10 ms windows
    double onset_floor = 0;      // m, least error any controller can have on that onset (see onset_floor())
};
// quick: gain scales {1, 2} x speeds {0.02, 0.05} m/s; full: gain scales {0.5, 1, 2} x speeds
// {0.01, 0.02, 0.05, 0.1} m/s. All at 1 kHz, with the default feed-forward, then the same speeds
// at gain scale 1 without it (the "before": seed 000's pure eq. 2). Rows per (scale, feed-forward),
// speeds ascending. The errors are NaN if the simulated device did not open (a bench must not
// report a 0 it did not measure).
std::vector<RollerTrackingRow> roller_tracking_table(bool quick);

// ---- Roller response to a jump of l_d ----------------------------------------------------------
// The roller alone (drivers/sim/roller_sine.hpp) at 1 kHz with the default gains: l_d jumps by
// 2 mm (0 -> 2 mm), 10 mm (-5 -> 5 mm) and 16 mm (-8 -> 8 mm, near the +-10 mm stops), and the
// settling into 0.05 mm (seed 001's 5 cm/s figure) is set against the force-limited least time.
struct RollerJumpRow {
    double jump = 0;             // m
    double jump_settle_s = 0;    // s, until |l_d - l| stays within `band`
    double force_limited_s = 0;  // s, least time with the drive on the rail (force_limited_jump_time)
    double band = 0;             // m
    double overshoot = 0;        // m, past the target
    double max_excursion = 0;    // m, furthest |nut| from the centre
    double half_travel = 0;      // m
};
// quick: the 10 mm jump only.
std::vector<RollerJumpRow> roller_jump_table(bool quick);

// The 1 cm peak-to-peak sine -3 dB frequency (Hz) of the roller alone at 1 kHz with the default
// gains (seed 000: about 8 Hz). quick: the sweep starts at 2 Hz (the motor's force does not
// saturate on that sine below ~7 Hz, so the crossing lies well above) and the bisection stops at
// 0.05 Hz; full: from 0.5 Hz, to 0.01 Hz. NaN when the gain never fell to -3 dB below 100 Hz.
double roller_bandwidth_hz(bool quick);

}  // namespace contactlab

namespace contactlab::drivers::sim {

// ---- Single measurements (what the tables are made of) ----------------------------------------

struct PressResult {
    bool opened = false;          // the device opened (nothing else is meaningful otherwise)
    bool faulted = false;
    ServoFault fault = ServoFault::none;
    double max_force = 0.0;       // N, commanded
    double max_speed = 0.0;       // m/s, finger
    double late_force_pp = 0.0;   // N, peak-to-peak force over the last 0.5 s
    double pp_third = 0.0;        // N, peak-to-peak force over the run's third quarter
    double pp_fourth = 0.0;       // N, and over its last quarter
    bool finite = true;
    double b_normal = 0.0;        // N s/m, arm damping along +y at the press point
    double b_declared = 0.0;      // N s/m
    double max_energy = 0.0;      // J, observer
};

// The hand comes down onto a floor of `stiffness` (N/m) from 5 mm above, over 0.3 s, and presses
// 2 mm into it (free space first: the engage gate), for `seconds` s at `rate` (Hz) with the hand's
// damping `hand_damping` (N s/m). `arm_counts` (per joint revolution) and `joint_friction` (N m)
// override the simulated arm's (ideal: 1 << 24 and 0).
// `limit_cycle`: the servo's limit-cycle detector reports (false: the passivity observer alone).
PressResult press_floor(double stiffness, double rate, double hand_damping, double seconds = 1.5,
                        int arm_counts = PlanarArmParams{}.encoder_counts,
                        double joint_friction = PlanarArmParams{}.friction, bool limit_cycle = true);

// Largest stiffness (N/m) at `rate` (Hz) on the rig, or `ideal` (24-bit encoders, no joint
// friction and the passivity observer without the limit-cycle detector: the sampling alone, so
// its limit is the bound's, not the detector's arming at the declared damping), by bisection on log K between `lo` (must hold) and `hi`, to a
// ratio of `resolution`. "Holds": no NaN, no runaway (finger under 1 m/s) and the passivity
// observer quiet for a 1 s press; with `settled` also the force ripple in the last quarter second
// below 0.1 N or below 0.9 x that of the quarter before (no limit cycle). Returns hi when even hi
// holds, 0 when lo does not (the bracket was wrong: no answer rather than a wrong one).
double largest_stable_k(double rate, double lo, double hi, bool settled, bool ideal, double resolution = 1.02);

// One row of the stability table at `rate` (Hz), bracket [0.05, 4] x 2 b / T.
StabilityRow stability_row(double rate, double resolution = 1.02);

// A press held for `seconds` (s) at `ratio` x the passivity bound (along the normal) at `rate`
// (Hz), classified (see AboveBoundOutcome).
AboveBoundProbe above_bound_probe(double rate, double ratio, double seconds = 3.0);

// Largest K in [lo, hi] (N/m) for which `holds` is true, by bisection on log K to a ratio of
// `resolution`, `holds` assumed monotone: hi when even hi holds, 0 when lo does not (the bracket
// was wrong: no answer rather than a wrong one).
template <class Holds>
double bisect_largest(double lo, double hi, double resolution, Holds&& holds) {
    if (!holds(lo)) return 0.0;
    if (holds(hi)) return hi;
    // On log K: the bound spans decades across rates, and a ratio is what the tables report.
    while (hi / lo > resolution) {
        const double mid = std::sqrt(lo * hi);
        (holds(mid) ? lo : hi) = mid;
    }
    return lo;
}

// A contact's force ripple has settled (N, peak-to-peak of the commanded force over a run's third
// and last quarter): small (< 0.1 N, above the quantisation limit cycle of a stable spring: K
// times a few encoder counts of ~18 um), or dying out (the last quarter's under 0.9 x the third's).
bool ripple_settled(double pp_third, double pp_fourth);

// What the servo's damper does, measured on a ServoTick at `rate` (Hz) with the scene's
// force.damping = `damping` (N s/m): a soft floor (100 N/m), the finger held 2 mm in, moved 10 um
// deeper in one tick, then held there; the proxy's force before safety.
struct DamperResponse {
    double applied = 0.0;    // N s/m: the force's damper part per m/s of sampled normal velocity,
                             //   (x_k - x_{k-1}) / T; `damping` when it divides by the period
    double after_stop = 0.0; // N: the damper part one tick after the finger stopped; 0 for a
                             //   backward difference of the last two samples (a filter remembers)
};
DamperResponse damper_response(double damping, double rate);
// damper_response(damping, rate).applied.
double effective_damping(double damping, double rate);

// One Z-width row at `rate` (Hz) and damping `damping` (N s/m); see ZWidthRow.
ZWidthRow zwidth_row(double rate, double damping, double resolution = 1.02);

struct BlockTracking {
    double max_measured = 0.0;  // m, |l_target - l_encoder|
    double rms_measured = 0.0;  // m, RMS of the same over the ticks sampled
    double max_tracking = 0.0;  // m, the same outside the jumps of l_d and their windows (RollerTrackingRow)
    double rms_tracking = 0.0;  // m
    double max_jump = 0.0;      // m, inside them
    int jumps = 0;              // jumps of l_d found
    std::uint64_t tracking_samples = 0;  // ticks outside the jumps' windows
    double max_element = 0.0;   // m, |l_target - l_element| (what the finger feels)
    double l_range = 0.0;       // m, how far l_d travelled
    double max_rate = 0.0;      // m/s, fastest l_d over 10 ms windows (encoder steps averaged out)
    // Against the true contact location (the proxy fed the simulated finger's unquantised pose),
    // over the tracking ticks (outside the jumps' windows) where that proxy is in contact too:
    double max_true_tracking = 0.0;  // m, |l_d true - l_element|: what the finger feels
    double rms_true_tracking = 0.0;  // m
    double max_staircase = 0.0;      // m, |l_d (from the encoders) - l_d true|: the quantisation itself
    double max_true_encoder = 0.0;   // m, |l_d true - l_encoder|: the nut, as seed 000 measured it
    double max_wire = 0.0;           // m, |l_element - l_encoder|: the wires' stretch and ringing
    std::uint64_t true_samples = 0;  // ticks in those
    std::uint64_t samples = 0;  // ticks sampled (engaged and in contact)
    bool opened = false;        // the device opened
};

// Seed 000's block task (drivers/tasks.hpp, on block_scene()) at hand speed `speed` (m/s) and
// servo rate `rate` (Hz) with roller gains `gains`, sampled while engaged and in contact.
// `stiffness` (N/m) replaces the scene's 1000 N/m when > 0: below ~1.5 kHz 1000 N/m is past the
// arm's 2 b / T and the loop (rightly) faults, so the low rates run a softer block.
// `rig` replaces the simulated device's parameters (e.g. finer encoders, to see what the
// quantisation costs).
BlockTracking block_task_tracking(double speed, double rate = 1000.0, const RollerGains& gains = RollerGains{},
                                  double stiffness = 0.0, const SimCldParams& rig = SimCldParams{});

// The least error (m) any controller can have on a target that starts moving at v (m/s) from
// rest, with the roller at rest: it learns of the motion up to one period T (s) late, and then
// needs v / a_max to reach v, falling behind by v^2 / (2 a_max). a_max (m/s^2) is the stall force
// less sliding friction over the mass reflected to the nut.
double onset_floor(double v, double T, const RollerParams& p = RollerParams{});

// Roller gains with the closed-loop poles moved from p0 = 400 rad/s (the defaults' placement,
// haptics/roller_controller.hpp) to scale x p0: the pole-placement formulas Kp = 3 tau p^2 / g,
// Ki = tau p^3 / g, Kd = (3 tau p - 1) / g scale as Kp s^2, Ki s^3, Kd s + (s - 1) / g, applied
// to the defaults so that scale 1 gives RollerGains{} exactly (their rounding kept). g (m/(V s))
// comes from `plant`. The derivative filter and the drive limit stay as they are; the re-placement
// of poles near the sampling is off (pole = 0): the gains are used as placed.
RollerGains roller_gains_scaled(double scale, const RollerParams& plant = RollerParams{});

}  // namespace contactlab::drivers::sim
