// trace_command.hpp — `contactlab trace` and `contactlab demo`: run the proxy over finger samples.
#pragma once

#include "engine/app/trace_csv.hpp"
#include "haptics/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace contactlab::app {

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
