// start_inside_warning.hpp — `trace` and `simulate` say so when the hand's first sample already
// has the pad inside a solid.
//
// The proxy starts where the first sample is, with no history (a proxy only knows which side of a
// wall it came from by having come from there). A run that starts with the pad 5 mm inside a
// floor therefore feels nothing until the pad leaves it: correct, but surprising, so it is said,
// with the time and the depth. The depth comes from the brute-force reference
// (haptics/verify/solid_reference.hpp), not from the proxy. Output is otherwise unchanged.
#pragma once

#include "haptics/scene.hpp"
#include "haptics/vec2.hpp"

#include <string>

namespace contactlab::app {

// m: a first pad deeper than this is reported (far below any depth a user would mean).
inline constexpr double kStartInsideReport = 1e-6;

// The warning line (without a newline) for a first sample at time t (s), finger centre x (m) and
// angle phi (rad), or "" when the pad is not inside a solid by more than kStartInsideReport.
std::string start_inside_warning(const char* command, const Scene& scene, double t, Vec2 x, double phi);

}  // namespace contactlab::app
