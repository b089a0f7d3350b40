// random_contact_scenes.hpp — seeded random environments and hand paths for the contact property
// test and the `contactlab fuzz-contact` soak.
//
// An environment mixes, around the origin:
//   * star-shaped closed solids (clockwise, so solid inside) whose edges are lines, arcs bulging
//     either way, quadratic and cubic curves: concave and convex corners, sharp and smooth;
//   * thin walls: closed rectangles 0.2-1 mm wide, 2-6 cm tall, at any angle;
//   * at most one terrain: an open chain from x = -0.25 to 0.25 m, left to right (solid below),
//     under everything else; hand paths keep the pad far from its two ends (the reference closes
//     it with a box below, solid_reference.hpp).
// A finger has R in [5, 30] mm and L in [0.2 R, 2 R]. A hand path is a sequence of strokes with
// small steps (1e-5 to 5e-4 m and at most 4e-3 rad a row): presses toward a surface point and up to
// 3 cm past it (as a hand does when the device's force saturates), slides, tilts and wanders.
// It starts with the pad clear of every solid.
//
// Everything is a function of the seed (a 64-bit mix of the soak's seed and the case number), so
// a failure is reproduced from those two numbers alone.
#pragma once

#include "haptics/scene.hpp"
#include "haptics/vec2.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::verify {

struct HandSample {
    Vec2 finger{0.0};  // x_f, m
    double phi = 0.0;  // rad
};

struct ContactCase {
    std::uint64_t seed = 0;
    Scene scene;                   // finger R, L; spring Ke 1000 N/m; no force clamp to speak of
    std::vector<HandSample> path;  // one row per servo tick
    std::string summary;           // e.g. "2 stars (quad, cubic, arc), thin wall, terrain; R 12.1 mm L 9.3 mm"
};

// True when the scene's contours neither cross themselves or each other nor lie one inside
// another, and it passes validate_scene: what every generated scene satisfies. Neighbouring
// segments are compared on chords within 1e-10 m, so a contour that turns back at a vertex and
// crosses itself a few micrometres away is caught.
bool contours_well_formed(const Scene& scene);

// The seed of case `index` of a soak seeded with `seed`.
std::uint64_t case_seed(std::uint64_t seed, std::uint64_t index);
// Rows the case with this seed will have (known before generating it): 300..900.
int case_rows(std::uint64_t case_seed);
// The case itself (a few ms: scenes are retried until valid and free of overlaps).
ContactCase make_contact_case(std::uint64_t case_seed);

}  // namespace contactlab::verify
