// safety.hpp — what stands between the rendered force and the motors (DESIGN.md "Threads and
// safety"): magnitude clamp (direction kept) then per-axis saturation, a NaN/Inf guard, the
// ramp-in after connect, fault clear or emergency-stop release, stall detection, and a passivity observer that
// turns a loop going unstable into a reported fault instead of a growing oscillation.
#pragma once

#include "haptics/vec2.hpp"

#include <cstdint>

namespace contactlab {

// |f| clamped to max_force (N) with its direction kept, then each component saturated to axis_max
// (N). Non-finite input gives zero.
Vec2 clamp_then_saturate(Vec2 f, double max_force, Vec2 axis_max) noexcept;

enum class ServoState : std::uint8_t {
    idle,        // no device / not started: output zero
    arming,      // no longer entered (kept so recorded state codes keep their numbers, see ramp_time)
    ramping,     // connected or re-armed: force scaled up linearly from 0 to 1 over the ramp time
    engaged,     // full force
    fault,       // output zero; see ServoFault
};

enum class ServoFault : std::uint8_t {
    none,
    non_finite_input,   // the device reported NaN/Inf for the finger or the roller
    non_finite_output,  // the renderer produced NaN/Inf (never passed on)
    watchdog,           // the tick stalled longer than the watchdog timeout
    instability,        // the passivity observer saw the loop generating energy
    device,             // the device reported a fault
};

const char* to_string(ServoState s) noexcept;
const char* to_string(ServoFault f) noexcept;

struct SafetyParams {
    // s: after connect, a fault cleared or the emergency stop released, the force scale rises
    // linearly from 0 to 1 over this time, starting at once, whatever the commanded force: the
    // user feels the wall come back within ramp_time, never above its steady Ke d (the scale is
    // at most 1). It used to wait, at zero, until the commanded force fell below 0.05 N, so a
    // finger resting in a wall after a switch felt nothing for as long as it stayed (issue 15).
    double ramp_time = 0.2;
    double fault_hold = 0.5;      // s: a fault holds output at zero at least this long
    double watchdog_timeout = 0.005;  // s: a gap between ticks longer than this is a stall
    bool latch_instability = true;    // an instability fault needs clear_fault() to re-arm
};

// Ramp-in and fault latch. step() returns the scale (0..1) applied to the force.
class SafetySupervisor {
public:
    void set_params(const SafetyParams& p) noexcept { p_ = p; }
    const SafetyParams& params() const noexcept { return p_; }

    void connect(double t) noexcept;             // device became ready at time t (s)
    void disconnect() noexcept;                  // back to idle
    void raise(ServoFault f, double t) noexcept; // enter fault at time t (s); first reason kept
    void clear_fault() noexcept { clear_requested_ = true; }

    // Once per tick at time t (s).
    double step(double t) noexcept;

    ServoState state() const noexcept { return state_; }
    ServoFault fault() const noexcept { return fault_; }
    ServoFault last_fault() const noexcept { return last_fault_; }
    std::uint32_t fault_count() const noexcept { return fault_count_; }

private:
    SafetyParams p_;
    ServoState state_ = ServoState::idle;
    ServoFault fault_ = ServoFault::none;
    ServoFault last_fault_ = ServoFault::none;
    std::uint32_t fault_count_ = 0;
    double since_ = 0.0;  // s: when the current state began
    bool clear_requested_ = false;
};

// Passivity observer (after Hannaford & Ryu 2002) for a sampled virtual environment rendered
// through a device with physical damping b (N s/m). Per tick it adds the energy the loop itself
// generated (haptics/energy_balance.hpp: the zero-order hold, the anisotropic field, the proxy's
// walk and friction, less what the device's damping dissipated along the spring's line of
// action; the hand's work through the finger angle and the user's scene edits are not the loop's
// and are left out). A passive loop keeps the sum at or below zero; a loop above the discrete bound
// K < 2b/T makes it grow every oscillation. The sum leaks with time constant `leak` so slow
// numerical drift is forgotten.
//
// A second sum counts only the intervals spent wholly in the spring's linear range (in contact,
// force below the clamp). Past the bound a loop can settle into a limit cycle that bounces between
// free flight and the force clamp: it gains energy only while crossing the linear range and loses
// it elsewhere, so the whole-cycle sum stays near zero and cannot see it; the linear-range sum
// grows by (K T / 2 - b) v^2 T a tick in those crossings and does.
struct PassivityParams {
    double threshold = 2e-3;       // J of net generated energy that counts as unstable
    double leak = 0.5;             // s
};

class PassivityObserver {
public:
    void set_params(const PassivityParams& p) noexcept { p_ = p; }
    const PassivityParams& params() const noexcept { return p_; }
    void reset() noexcept {
        energy_ = linear_energy_ = 0.0;
        prev_linear_ = false;
    }
    // generated: the energy (J) the loop generated over the last period dt (s) (negative when it
    // dissipated); linear: in contact with the force below the clamp now. Returns true once either
    // sum passes the threshold. Non-finite input resets the sums and returns false.
    bool step(double generated, double dt, bool linear = false) noexcept;
    double energy() const noexcept { return energy_; }  // J
    double linear_energy() const noexcept { return linear_energy_; }  // J
    // J: how much more the loop may generate before either sum reports (the observer's budget).
    double margin() const noexcept { return p_.threshold - sum(); }
    // The share of the budget used (1: a report; negative while the loop has dissipated more than
    // it made): what the editor plots.
    double used() const noexcept { return p_.threshold > 0.0 ? sum() / p_.threshold : 0.0; }

private:
    double sum() const noexcept { return energy_ > linear_energy_ ? energy_ : linear_energy_; }  // J, the larger
    PassivityParams p_;
    double energy_ = 0.0;
    double linear_energy_ = 0.0;  // J
    bool prev_linear_ = false;
};

}  // namespace contactlab
