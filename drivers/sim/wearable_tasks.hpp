// wearable_tasks.hpp — seed 003's experiments on the simulated wearable platform
// (haptics/wearable/rig.hpp), in virtual time, for `contactlab simulate --device sim-wearable`:
//
//   step       Fig. 7: a 0.3 N step on every cable's reference Q_r; rise time and steady error of
//              the estimated tensions Q-hat (the seed's figure plots Q-hat).
//   bandwidth  §3.7: a sine sweep of Q_r about 0.15 N (the seed's Fig. 8 sine,
//              Q_r = 0.15 sin(pi t) + 0.15 N, is the sweep's first point); -3 dB frequency of Q-hat.
//   curvature  §4, Fig. 9: a virtual arc of chord d and height h moves under the still fingertip;
//              position control (Fig. 6) tilts the platform to the arc's slope under the contact
//              and presses with the contact force; tilt tracking against the surface angle.
#pragma once

#include "haptics/wearable/rig.hpp"

#include <array>
#include <vector>

namespace contactlab::drivers::sim {

struct WearableSample {
    double t = 0.0;                                  // s
    Eigen::Vector3d reference = Eigen::Vector3d::Zero();  // Q_r (N)
    Eigen::Vector3d estimate = Eigen::Vector3d::Zero();   // Q-hat (N)
    Eigen::Vector3d tension = Eigen::Vector3d::Zero();    // the plant's Q (N)
    bool fault = false;
};

struct WearableStepDef {
    double step = 0.3;        // N on every cable (seed: Q_r,i = 0.3 N)
    double t_step = 0.05;     // s before the step
    double duration = 0.8;    // s in all
    double sample_period = 1e-3;  // s between samples
    double settle_window = 0.3;   // s at the end over which the steady error is measured
};
struct WearableStepResult {
    std::vector<WearableSample> samples;
    double rise_time_s = 0.0;        // 10 % -> 90 % of the step, slowest cable's Q-hat (s)
    double steady_error_pct = 0.0;   // max over cables |mean Q-hat - Q_r| / Q_r over the window (%)
    double overshoot_pct = 0.0;      // max over cables (max Q-hat - Q_r) / Q_r (%)
    bool fault = false;              // a control or estimate fault occurred
};
WearableStepResult wearable_step(const wearable::RigDef& rig, const WearableStepDef& def = {});

struct WearableSineDef {
    double offset = 0.15;     // N (seed Fig. 8)
    double amplitude = 0.15;  // N
    int settle_cycles = 2;
    int measure_cycles = 4;
    double min_settle = 0.3;  // s, at least this long before measuring
    double sample_period = 1e-3;  // s
};
struct WearableSineResponse {
    double freq = 0.0;   // Hz
    double gain = 0.0;   // |fundamental of Q-hat| / amplitude, mean over the cables
    double phase = 0.0;  // rad, Q-hat relative to Q_r (negative: lag)
};
// One frequency; `samples`, when given, receives the run (t, Q_r, Q-hat, Q).
WearableSineResponse wearable_sine(const wearable::RigDef& rig, const WearableSineDef& def, double freq,
                                   std::vector<WearableSample>* samples = nullptr);

struct WearableBandwidthResult {
    double bandwidth_hz = 0.0;  // first frequency where the gain falls to 1/sqrt(2)
    bool found = false;
    std::vector<WearableSineResponse> sweep;  // by frequency
};
// Log sweep from min_freq (the seed's 0.5 Hz) to max_freq, then bisection to `tolerance` Hz.
WearableBandwidthResult wearable_bandwidth(const wearable::RigDef& rig, const WearableSineDef& def = {},
                                           double min_freq = 0.5, double max_freq = 45.0, int per_decade = 8,
                                           double tolerance = 0.05);

struct CurvatureArcDef {
    double chord = 0.30;         // m, d (seed: 30 cm)
    double height = 0.02;        // m, h (seed: 10, 20, 30 mm)
    double speed = 0.05;         // m/s, the arc's speed under the finger (not in the seed)
    double margin = 0.02;        // m of travel before and after the chord (out of contact)
    double contact_force = 0.5;  // N, the normal force pressed while on the arc (not in the seed)
    double sample_period = 0.01; // s: one row per link tick
    double settle = 0.2;         // s after contact starts that the rms leaves out (the press-in)
    // Seed 003's task B: the arc moves the other way under the finger (the contact runs from +x to
    // -x). false: task A, from `margin` before the chord's -x end to `margin` past its +x end.
    bool reverse = false;
};
struct CurvatureSample {
    double t = 0.0;              // s
    double contact_x = 0.0;      // m, the contact's position along the chord (arc frame, 0 mid-chord)
    double surface_angle = 0.0;  // rad, the arc's slope there: -asin(x / r_a), positive rising toward +x
    double platform_tilt = 0.0;  // rad, the simulated platform's roll (its tilt along the finger)
    double platform_force = 0.0; // N, |force| of the fingertip's wrench on the platform; 0 off the arc
    Eigen::Vector3d tension = Eigen::Vector3d::Zero();  // Q (N)
    bool contact = false;
    bool fault = false;
};
struct CurvatureArcResult {
    std::vector<CurvatureSample> samples;
    double radius = 0.0;          // m, r_a = (d^2/4 + h^2) / (2h)
    double tilt_rms = 0.0;        // rad, rms(platform_tilt - surface_angle) in contact after `settle`
    double tilt_max_error = 0.0;  // rad
    double max_surface_angle = 0.0;  // rad, asin(d / (2 r_a))
    bool fault = false;
};
// Throws std::invalid_argument for a chord or height that makes no arc.
CurvatureArcResult curvature_arc(const wearable::RigDef& rig, const CurvatureArcDef& def);

}  // namespace contactlab::drivers::sim
