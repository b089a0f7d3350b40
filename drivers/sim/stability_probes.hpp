// stability_probes.hpp — the contact scenarios the stability tests and the bench's stability
// table run on the simulated CLD rig (encoder quantisation, joint friction, 1.5 N clamp): a press
// onto a floor, a press held at the clamp, sliding along the floor, seed 000's block task over a
// convex corner, and taps at hand speeds; optionally with jittered servo periods. One definition,
// so what a test asserts and what the table prints are the same closed loop. Virtual time, SI.
#pragma once

#include "haptics/servo_tick.hpp"

#include <cstdint>

namespace contactlab::drivers::sim {

enum class ContactScenario : std::uint8_t {
    press,       // from 5 mm above to 2 mm into a floor over 0.3 s, then held (0.6 N of hand force)
    press_hard,  // the same to 6 mm in: the hand's 1.8 N holds the spring on its 1.5 N clamp
    slide,       // pressed 2 mm in, then a 6 cm stroke out and back each second (up to 0.19 m/s)
    corner,      // seed 000's block task at 5 cm/s: along the top, over the edge, down the face
    taps,        // 4 taps a second from 6 mm above to 3 mm in (hand speed up to 0.11 m/s)
    hard_taps,   // 5 taps a second from 6 mm above to 14 mm in (up to 0.31 m/s, 4 N of push)
};
const char* to_string(ContactScenario s) noexcept;

struct ScenarioRun {
    bool opened = false;          // the device opened (nothing else is meaningful otherwise)
    bool faulted = false;         // any fault reported
    ServoFault fault = ServoFault::none;  // the first one
    InstabilityCause cause = InstabilityCause::none;
    double fault_time = -1.0;     // s after the first tick in contact; < 0: no fault
    double contact_time = -1.0;   // s, virtual time of the first tick in contact
    double max_force = 0.0;       // N, largest commanded force magnitude
    double max_force_after_fault = 0.0;  // N, largest commanded after the fault (0: output zeroed)
    double max_speed = 0.0;       // m/s, fastest true finger speed
    double late_force_pp = 0.0;   // N, peak-to-peak of the commanded |F| over the last 0.5 s
    double pp_third = 0.0;        // N, peak-to-peak of the commanded |F| over the run's third quarter
    double pp_fourth = 0.0;       // N, and over its last quarter (is a ripple dying out?)
    double ripple_fourth = 0.0;   // N, peak-to-peak over the last quarter of |F| less its 20 ms
                                  //   centred mean (what the hand's motion does to |F| left out)
    // Over the last 0.5 s, ticks in contact: the mean of |F_k - F_{k-1}| and the mean |F| (N). A
    // loop held quiet (by the passivity controller, say) steps by a small fraction of its force.
    double late_mean_step = 0.0;
    double late_mean_force = 0.0;
    double max_passivity_damping = 0.0;  // N s/m, the most the passivity controller added
    bool finite = true;           // every force and finger reading finite
    double b_declared = 0.0;      // N s/m, the device's declared (lowest) damping
    double b_normal = 0.0;        // N s/m, the arm's damping along +y where the press ends
};

struct ScenarioOptions {
    double seconds = 3.0;         // s of virtual time (corner: the task's own length)
    double hand_damping = 0.0;    // N s/m: none, so the arm's b is all the damping there is
    double jitter = 0.0;          // each period T (1 + jitter u), u uniform in [-1, 1], seeded
    std::uint32_t seed = 1;
    double damping = 0.0;         // B, N s/m: the scene's force.damping (the proxy's normal damper)
    PassivityMode passivity = PassivityMode::fault;  // the servo's answer to a loop generating energy
};

// Runs `scenario` with spring stiffness `stiffness` (N/m) at servo rate `rate` (Hz).
ScenarioRun run_contact_scenario(ContactScenario scenario, double rate, double stiffness,
                                 const ScenarioOptions& opt = {});

// The damping (N s/m) the rig declares for `scenario`: the lowest over its hand path's box.
double declared_damping(ContactScenario scenario);

// The discrete passivity bounds (N/m) at `rate` (Hz): 2 b / T with the damping the scenario's rig
// declares (what the servo knows; its limit-cycle detector arms above it) and with the arm's
// damping along the press's normal (its actual b under the press, the larger).
struct PassivityBounds {
    double declared = 0.0;  // N/m
    double normal = 0.0;    // N/m
};
PassivityBounds passivity_bounds(double rate, ContactScenario scenario = ContactScenario::press);

}  // namespace contactlab::drivers::sim
