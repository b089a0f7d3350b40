// finger_sweep.hpp — seed 003's trial on a display that moves no hand (the wearable platform):
// the finger is held still and an arc moves under it at constant speed. What the finger feels is
// the same as the finger passing over the still arc, so the sweep is written that way: the
// finger comes down onto x0 from 15 mm above in 0.3 s and settles for 0.3 s (as the simulated
// trial's hand, so the finger never appears inside the surface), then its centre goes from x0 to
// x1 at `speed`, at the height where its circle (radius R) rests on the stimulus less `press`, its
// pad level (phi 0: the platform tilts, not the finger).
//
// The stimulus is the curvature task's (haptics/stimuli.hpp, generate_arc): a floor at y = 0 with
// a circular cap of chord c and height h on it. Where a circle rests on it is the highest of what
// it rests on alone: the floor beside the cap (R above it), the cap (R + r_a from its centre,
// while that direction meets the cap) and the cap's two corners (R from each). Plain functions of
// a few doubles: the servo thread evaluates them every tick (no allocation, no lock).
#pragma once

#include "haptics/vec2.hpp"

namespace contactlab::drivers {

struct FingerSweep {
    double x0 = 0.0, x1 = 0.0;      // m: the finger centre's start and end (x1 < x0: right to left)
    double speed = 0.1;             // m/s along x
    double finger_radius = 0.010;   // m, R
    double press = 0.003;           // m below the resting height
    double chord = 0.30;            // m, the cap's chord c on the floor y = 0, centred on x = 0
    double height = 0.02;           // m, the cap's height h (> 0)
};

inline constexpr double kSweepDescent = 0.3, kSweepSettle = 0.3;  // s before the pass
inline constexpr double kSweepAbove = 0.015;                        // m above the press at x0

// Seconds of the pass from x0 to x1 (after the descent and the settling).
double finger_sweep_duration(const FingerSweep& s);
// Height (m) of the centre of the finger's circle resting on the stimulus at x (m).
double finger_sweep_resting_height(const FingerSweep& s, double x);
// The finger's centre t seconds into the sweep: coming down onto x0 until kSweepDescent, held
// there until kSweepDescent + kSweepSettle, then the pass; held at x1 after it.
Vec2 finger_sweep_at(const FingerSweep& s, double t);

}  // namespace contactlab::drivers
