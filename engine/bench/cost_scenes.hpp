// cost_scenes.hpp — the scenes and finger strokes `contactlab bench` times the proxy on.
//
// Two ways a scene grows (issue 8):
//   extent   a longer contour at constant segment length: N pieces each 5 mm wide along a terrain
//            of two sinusoids (8 mm peak), so 100,000 segments run for 500 m;
//   dense    the same 0.4 m sinusoid (1 cm amplitude, 10 cm wavelength) cut into N pieces, so at
//            100,000 segments thousands of 4 um pieces lie under the pad.
// Each is built of lines, of arcs (a circle through each piece's ends and midpoint), or of
// quadratic Beziers (through each piece's ends, passing the profile's midpoint), the same profile
// either way. The stroke slides the finger 1 mm deep along the profile's normal, pad facing down,
// 4000 ticks: over the middle 0.4 x length (at most 2 m) for extent, the middle 0.2 m for dense
// (50 um a tick: 5 cm/s at 1 kHz).
#pragma once

#include "haptics/finger_samples_csv.hpp"
#include "haptics/scene.hpp"
#include "haptics/vec2.hpp"

#include <string>
#include <vector>

namespace contactlab::bench {

enum class SegmentKind { lines, arcs, curves };
enum class Growth { extent, dense };

struct CostCase {
    SegmentKind kind = SegmentKind::lines;
    Growth growth = Growth::extent;
    int segments = 10;
};

// "lines", "arcs", "curves", with "_dense" for the density growth: the JSON key of issue 8.
std::string case_key(SegmentKind kind, Growth growth);

Scene cost_scene(const CostCase& c);

// One sample per 1 ms tick.
std::vector<FingerSample> cost_stroke(const CostCase& c, int ticks = 4000);

}  // namespace contactlab::bench
