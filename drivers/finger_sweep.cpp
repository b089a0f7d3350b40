// finger_sweep.cpp — the finger's pass over the curvature task's arc (finger_sweep.hpp).
#include "drivers/finger_sweep.hpp"

#include "haptics/stimuli.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::drivers {

double finger_sweep_duration(const FingerSweep& s) { return s.speed > 0.0 ? std::abs(s.x1 - s.x0) / s.speed : 0.0; }

double finger_sweep_resting_height(const FingerSweep& s, double x) {
    const double R = s.finger_radius, half = 0.5 * s.chord;
    // The cap: the circle through (-c/2, 0), (0, h), (c/2, 0), radius r_a, centre (0, h - r_a).
    const double ra = arc_cap_radius(s.chord, s.height);
    const double cy = s.height - ra;
    double best = std::abs(x) >= half ? R : -1e9;  // the floor, beside the cap
    // On the cap: the centre R + r_a from the cap's centre, in a direction that meets the cap
    // (|dx| / (R + r_a) within the corners' c/2 / r_a).
    const double reach = R + ra;
    if (std::abs(x) <= reach * (half / ra)) best = std::max(best, cy + std::sqrt(reach * reach - x * x));
    // On a corner (+-c/2, 0).
    for (const double corner : {-half, half})
        if (const double dx = x - corner; std::abs(dx) <= R) best = std::max(best, std::sqrt(R * R - dx * dx));
    return best;
}

Vec2 finger_sweep_at(const FingerSweep& s, double t) {
    if (t < kSweepDescent) {  // coming down from above x0
        const double pressed = finger_sweep_resting_height(s, s.x0) - s.press;
        return {s.x0, pressed + kSweepAbove * (1.0 - std::max(0.0, t) / kSweepDescent)};
    }
    const double T = finger_sweep_duration(s), pass = t - kSweepDescent - kSweepSettle;  // s
    const double u = T > 0.0 ? std::clamp(pass / T, 0.0, 1.0) : 0.0;
    const double x = s.x0 + (s.x1 - s.x0) * u;
    return {x, finger_sweep_resting_height(s, x) - s.press};
}

}  // namespace contactlab::drivers
