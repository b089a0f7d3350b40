// contour_crossing.hpp — where a closed contour crosses itself or another closed contour.
//
// Why: a closed contour is the outline of a solid, solid on its right. One that crosses itself
// (a bow-tie, a figure 8) or another closed one has no consistent solid: across the crossing
// "the right" of one branch is the free side of the other, and the god-object proxy sticks at
// the crossing, holding the force clamp while the finger moves away. scene_io refuses such
// scenes with the point found here. Open chains (terrain profiles) may cross anything.
//
// What counts (the rule scenes/README.md states):
//   * a crossing: two branches of the closed contours pass through each other at a point, the
//     curves at an interior point of each, or one of them (or both) through a vertex: the four
//     directions leaving the point alternate between the two branches. Neighbouring segments
//     share their joint, which is not a crossing (the closing joint of a closed contour too).
//   * a touch is not a crossing: two solids meeting at a corner, a vertex on another edge with
//     the contour staying on its side, tangent arcs, two stretches running along each other.
//     The solid stays on the same side of every branch, so the proxy sees a consistent (if
//     pinched) solid. Where directions tie (tangent branches), the curvature decides.
//
// Geometry: lines and arcs exactly (analytic line/line, line/circle, circle/circle roots, a
// tangency snapped to one point within the roots' rounding); quadratic and cubic Beziers on
// their chords within kCrossingCurveTolerance (bezier.hpp's polyline, the scenes' join tolerance),
// so a crossing of curves is found unless the sliver between them is thinner than about twice
// that, and curves that pass nearer than that without crossing may read as crossing. Points
// within kCrossingPointTolerance of each other are one point (segments join within 1e-9 m); near
// a joint whose two directions differ by theta, within kCrossingPointTolerance / sin(theta).
//
// Cost: the pieces of the closed contours go into an AabbTree; each piece is tested only against
// those whose boxes overlap its own: O(n log n + k), never all pairs (timed by
// tests/bench/bench_scene_checks.cpp, counted by tests/haptics/test_contour_crossing.cpp). Open
// contours cost nothing.
#pragma once

#include "haptics/scene.hpp"
#include "haptics/vec2.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace contactlab {

// m: Bezier curves are tested on chords within this of the curve. Why this fine: where a contour
// turns back at a vertex, two neighbouring curves can cross again a few micrometres away in a
// sliver tens of nanometres wide (contactlab fuzz-contact found such scenes), and the proxy reads
// that tip by its tangents as the opposite corner. A 5 cm circle of cubics is 16,000 chords.
// For a curve larger than 1 m (its control points' box), this times its size in metres.
inline constexpr double kCrossingCurveTolerance = 1e-9;
// m: points closer than this are the same point (4 times the scenes' join tolerance).
inline constexpr double kCrossingPointTolerance = 4e-9;

struct ContourCrossing {
    // The pair found first in (contour, segment) order: a before b. a == b's contour for a
    // contour that crosses itself.
    int contour_a = 0, segment_a = 0;
    int contour_b = 0, segment_b = 0;
    Vec2 point{0.0};  // m, where they cross (within the tolerances above)
};

// What one search did: the closed contours' pieces (curves as their chords), and the pairs of
// them it tested exactly (those whose boxes overlap; all pairs would be n (n - 1) / 2). Tests
// hold the search to its O(n log n + k) with these counts, not with a clock.
struct CrossingSearchWork {
    int pieces = 0;
    std::int64_t pairs_tested = 0;
};

// The first crossing of the closed contours (in the order of their pieces), or none. The
// contours must already be valid segment by segment, with joined ends (scene_io's rules).
// `work`, if given, receives what the search did.
std::optional<ContourCrossing> find_contour_crossing(const std::vector<Contour>& contours,
                                                     CrossingSearchWork* work = nullptr);

}  // namespace contactlab
