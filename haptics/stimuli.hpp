// stimuli.hpp — generators for the seeds' experimental stimuli, as scenes.
//
//   bumps  seed 002 §2.2-2.3: a slowly varying base (sum of 20 sinusoids) sampled every 2 mm, with
//          small (3 mm) and large (18 mm) bumps of 10 control points each, the polygonal envelope
//          turned into G1 quadratic Beziers through the midpoints of its edges (eq. 2).
//   block  seed 000 Fig. 9: the contour-following block, top length d before the edge.
//   arc    seed 003's curvature stimuli: a circular bump of chord c and height h on a floor.
// Same definition (and seed), same scene, bit for bit: randomness comes from a fixed generator
// (splitmix64) and its own uniform mapping, not from the standard library's distributions.
#pragma once

#include "haptics/scene.hpp"

#include <cstdint>
#include <vector>

namespace contactlab {

struct BumpsDef {
    std::uint64_t seed = 1;
    int small_bumps = 2;          // count of 3 mm bumps
    int large_bumps = 1;          // count of 18 mm bumps
    double length = 0.184;        // m: traced length (seed 002: 18.4 cm)
    double base_span = 0.20;      // m: the base shape is scaled to this vertical span (issue #3)
    double sample_step = 0.002;   // m: base sampling interval (seed 002: 2 mm)
    double small_height = 0.003;  // m
    double large_height = 0.018;  // m
    double min_width = 0.015, max_width = 0.030;      // m, bump widths
    double min_spacing = 0.015, max_spacing = 0.057;  // m, gap between consecutive bumps
};

// What the generator placed, for tests and captions.
struct BumpPlacement {
    double start = 0.0;   // m, x of the bump's first control point
    double width = 0.0;   // m
    double height = 0.0;  // m, nominal (the envelope's)
    bool large = false;
};

struct GeneratedScene {
    Scene scene;
    std::vector<BumpPlacement> bumps;
    std::vector<Vec2> envelope;  // the polygon the curves are built from (m)
};

// Throws std::invalid_argument (naming the option) when the bumps cannot fit or a value is absurd.
GeneratedScene generate_bumps(const BumpsDef& def);

// Seed 000's block: top at y = 0 ending at the edge x = 0, starting at x = -(d + 0.10) m; the far
// face drops `drop` m to a floor running `floor` m on. d in [0.04, 0.10] m in the seed.
Scene generate_block(double d, double drop = 0.10, double floor = 0.16);

// Seed 003's curvature stimulus: a convex circular arc of chord `chord` and height `height` (m)
// centred at x = 0 on a floor at y = 0 that extends `margin` m on each side.
Scene generate_arc(double chord, double height, double margin = 0.05);
// That arc's radius r_a (m): the circle through (-c/2, 0), (0, h), (c/2, 0), (c^2/4 + h^2) / 2h
// (seed 003 section 4); its centre is (0, h - r_a).
inline double arc_cap_radius(double chord, double height) { return (0.25 * chord * chord + height * height) / (2.0 * height); }

}  // namespace contactlab
