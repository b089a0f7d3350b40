// trace_command.hpp — `contactlab trace` and `contactlab demo`: run the proxy over finger samples.
#pragma once

#include "engine/app/trace_csv.hpp"
#include "haptics/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace contactlab::app {

// Values given on the command line replace the scene file's (SI units).
struct SceneOverrides {
    std::optional<double> stiffness;  // N/m   (--stiffness)
    std::optional<double> radius;     // m     (--radius)
    std::optional<double> length;     // m     (--length)
    std::optional<double> max_force;  // N     (--max-force)
    std::optional<std::string> curve_mode;  // exact | flatten (--curve-mode)
    std::optional<double> tolerance;        // m, flatten chord tolerance (--tolerance)
    std::optional<std::string> force_model; // spring | ellipsoid (--force-model)
    std::optional<double> k_tangential;     // N/m (--k-tangential)
    std::optional<double> k_normal;         // N/m (--k-normal)
    std::optional<double> eccentricity;     // k_normal / k_tangential (--eccentricity)
    std::optional<double> total_stiffness;  // N/m, seed 004 eq. 3 (--total-stiffness)
    std::optional<double> friction;         // static coefficient (--friction)
    std::optional<double> friction_dynamic; // dynamic coefficient, default = static (--friction-dynamic)
    std::optional<double> damping;          // N s/m (--damping)
    std::optional<std::string> contact_force; // proxy | sum: force with two contacts (--contact-force)
};

// Applies the overrides and re-validates; a bad value throws SceneError naming the option.
void apply_overrides(Scene& scene, const SceneOverrides& o);

// Runs the arc-pad proxy over the samples (one tick per sample, starting at the first sample
// with no history) and returns one output per sample.
std::vector<ProxyOutput> run_trace(const Scene& scene, const std::vector<FingerSample>& samples);

// Writes the trace CSV atomically (temporary file beside `path`, then rename).
void write_trace_file(const std::string& path, const std::vector<FingerSample>& samples,
                      const std::vector<ProxyOutput>& outputs);

// The headless demo's scripted hand: a contour-following finger, as in seed 000's block task. It
// descends at `x0` (m) until contact, then each 1 ms tick moves `speed` (m/s) along the surface
// tangent while pressing `press` (m) into it along the contact normal, and tips the finger angle
// (at most 1 rad/s) so the pad's middle faces the surface. Runs for `duration` (s).
struct DemoRun {
    std::vector<FingerSample> samples;
    std::vector<ProxyOutput> outputs;
};
DemoRun run_contour_follow(const Scene& scene, double x0, double speed, double press, double duration);

}  // namespace contactlab::app
