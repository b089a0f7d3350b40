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
    // Blocks a run (8 mm at seed 002's 0.25 mm points): the run that holds the answer has its
    // blocks tested one by one, so shorter runs test fewer (against 8 blocks, 12 % fewer
    // instructions for seed 002's heights; 3, or blocks of 4, 6 or 16 points, were no better).
    static constexpr std::size_t kRun = 4;
    // A line no point of a block rises above (m): y <= y0 + slope (x - x0) + above for each of
    // its points, with x in [x0, x1]. On a sloping surface it bounds a block's points far more
    // closely than its highest point does (that point lies at one end), so that the circle
    // resting on it can be ruled out without looking at the points (resting_height).
    struct BlockLine {
        double x0 = 0.0, x1 = 0.0;  // m: the block's first and last point's x
        double y0 = 0.0;            // m
        double slope = 0.0;         // the chord's, from the first point to the last (0 where steep or vertical)
        double above = 0.0;         // m: the most a point lies above the chord, and a rounding allowance
        double root = 1.0;          // sqrt(1 + slope^2)
        double lean = 0.0;          // slope / root: where on a circle of radius r the line touches it, in r
    };
    std::vector<Vec2> pts;          // m, by x
    std::vector<double> block_top;  // m: max y over pts[i * kBlock, (i + 1) * kBlock)
    std::vector<double> run_top;    // m: max of block_top[i * kRun, (i + 1) * kRun)
    std::vector<BlockLine> block_line;
    std::vector<BlockLine> run_line;  // the same over each run of kRun blocks
};

SurfaceProfile profile_of(std::vector<Vec2> pts);

// Where a hand moving along x last found its answers: the point that held the circle and the
// points within reach. Any value is valid (a fresh cursor, or one from elsewhere on the profile);
// one from the last sample, a few um away, saves the searches.
struct RestingCursor {
    std::size_t hint = 0;        // the point the last answer came from (an index into pts)
    std::size_t lo = 0, hi = 0;  // the last query's points within reach: [lo, hi)
    bool span_valid = false;     // lo and hi are a query's on this profile (else they are searched)
};

// Height (m) of the centre of a circle of radius r (m) resting from above at x (m) on the points:
// the highest q.y + sqrt(r^2 - dx^2) over the points with |dx| <= r, dx = q.x - x; -1e9 when
// none is within r. Bit for bit the maximum a scan of every point gives. The cursor is where the
// last answer was found (above); it is updated.
double resting_height(const SurfaceProfile& s, double x, double r, RestingCursor& cursor);
// The same with only the point of the last answer (`hint`, an index into pts; any value is valid).
double resting_height(const SurfaceProfile& s, double x, double r, std::size_t& hint);

}  // namespace contactlab::experiments
