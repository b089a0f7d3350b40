// surface_profile.hpp — the height at which a circle (the finger pad's arc, radius r) rests on
// a contour from above: what the simulated hand follows when it slides along a task's surface
// (stimulus.cpp's hand paths, seeds 002 and 003).
#pragma once

#include "haptics/vec2.hpp"

#include <cstddef>
#include <vector>

namespace contactlab::experiments {

// A contour sampled as points (m), sorted by x, with the highest y of each block of kBlock of
// them and of each run of kRun blocks, so that a resting height looks at a few blocks instead of
// every point, and passes over a run that cannot reach the best height in one test.
struct SurfaceProfile {
    static constexpr std::size_t kBlock = 8;
    static constexpr std::size_t kRun = 8;  // blocks
    std::vector<Vec2> pts;          // m, by x
    std::vector<double> block_top;  // m: max y over pts[i * kBlock, (i + 1) * kBlock)
    std::vector<double> run_top;    // m: max of block_top[i * kRun, (i + 1) * kRun)
};

SurfaceProfile profile_of(std::vector<Vec2> pts);

// Height (m) of the centre of a circle of radius r (m) resting from above at x (m) on the points:
// the highest q.y + sqrt(r^2 - dx^2) over the points with |dx| <= r, dx = q.x - x; -1e9 when
// none is within r. Bit for bit the maximum a scan of every point gives. `hint` is where the
// last answer was found (an index into pts; any value is valid): a hand moving a few um a sample
// finds its answer there first, which lets the bound skip most of the rest. It is updated.
double resting_height(const SurfaceProfile& s, double x, double r, std::size_t& hint);

}  // namespace contactlab::experiments
