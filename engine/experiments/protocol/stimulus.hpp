// stimulus.hpp — each task's stimulus for one trial: the scene (made by haptics/stimuli.hpp's
// generators, as `contactlab generate` writes them) and the scripted hand's path over it.
//
//   contour-following  seed 000's block of length d; the hand descends onto the top at d + 1 cm
//                      from the edge, slides to `overshoot` past it, tips round it and descends
//                      the far face (drivers/tasks.hpp)
//   bump-counting      seed 002's bumps: k bumps, each small or large at random; the hand slides
//                      the traced length left to right at the protocol's speed, `press` below the
//                      height at which the finger's circle rests on the surface
//   curvature          seed 003's arc of chord d and height h; motion A slides across it left to
//                      right, motion B right to left (the seed's S1E1 and S2E2 in a plane)
//   surface-orientation seed 004's field over a flat floor (friction holds the stiction point);
//                      the hand presses 1 mm in, then probes 1 mm along each downward diagonal
//   edge-sharpness     a ridge: two faces at +-`edge.slope_deg` joined by a tangent arc of the
//                      edge's radius (line-arc-line); the hand slides across it left to right
//                      like the curvature task. A trial has two intervals, the reference edge
//                      and the comparison (reference + stimulus mm), in the order
//                      comparison_interval() draws; make_stimulus gives the first interval's,
//                      make_edge_stimulus either.
#pragma once

#include "drivers/hand_path.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "haptics/scene.hpp"

namespace contactlab::experiments {

struct Stimulus {
    Scene scene;
    drivers::HandPath path;
    double slide_start = 0.0, slide_end = 0.0;  // s: when the hand slides (bumps, curvature)
    int small_bumps = 0, large_bumps = 0;       // bump counting
    // Surface orientation: the probes' times (s): [0] down-left out, [1] down-left extreme,
    // [2] down-right out, [3] down-right extreme.
    double probe[4] = {0, 0, 0, 0};
};

// What the stimulus's hand path is for. `script`: a scripted hand follows it, positions and
// finger angles. `envelope`: a hand that steers by feel reads only its positions (the rig's box),
// its first sample and where its slide ends; the finger angles after the first sample are then
// left at the first's (bump counting and curvature honour it; bump counting's feel hand asks for
// it: the angle from the surface's slope over +-15 mm was about half of making a seed 002 path).
enum class PathUse { script, envelope };

// Contour following: `overshoot` (m) past the edge before tipping, `top_speed` (m/s) along the
// top and round the corner (0: the protocol's hand speed, which the far face always takes).
Stimulus make_stimulus(const Protocol& p, const Condition& c, const PlannedTrial& t, double overshoot = 0.0,
                       double top_speed = 0.0, PathUse use = PathUse::script);

// Curvature: where the slide across the arc starts (m): 2 cm before the arc, on the left for
// motion A (which ends as far on the right), on the right for B. The live sweep starts there too.
double curvature_slide_start(const Protocol& p, const Condition& c);

// Edge sharpness: the edge of radius `radius` (m) and the slide across it.
Stimulus make_edge_stimulus(const Protocol& p, double radius);
// The radius (m) of a trial's edge in `interval` (1 or 2).
double edge_radius(const Protocol& p, const PlannedTrial& t, int interval);
// The ridge alone: faces at +-slope (rad) out to +-half_width (m) from the apex, joined by a
// tangent arc of `radius` (m); solid below.
Scene generate_edge(double radius, double slope, double half_width);

// How many intervals a task's surface points cut a segment into (a point about every 0.25 mm, for
// the hand's resting heights): ceil(segment_length(seg) / 0.25 mm), at least 2.
int surface_intervals(const Segment& seg);

// Seed 003: the force direction's range (deg) sliding over a whole arc of chord d and height h,
// twice the slope at its ends: 2 asin(d / (2 r_a)), r_a = (d^2 / 4 + h^2) / (2 h) (seed 003 §4).
double arc_slope_range_deg(double chord, double height);

}  // namespace contactlab::experiments
