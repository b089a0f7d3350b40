// environment.hpp — a scene's contours compiled for the servo: flat segments with their
// neighbours, free-side normals, the normal cones of convex vertices, and a spatial index.
//
// Built once per scene edit, off the servo thread; immutable afterwards, so the servo can read
// it without locks.
#pragma once

#include "haptics/aabb_tree.hpp"
#include "haptics/bezier.hpp"
#include "haptics/scene.hpp"

#include <limits>
#include <vector>

namespace contactlab {

// A CCW interval of angles [start, start + width] (rad), width in [0, 2 pi].
struct AngleSpan {
    double start = 0.0;
    double width = 0.0;
};

struct EnvSegment {
    enum class Kind : std::uint8_t { line, arc };
    Kind kind = Kind::line;
    Vec2 start{0.0};  // m, travel order
    Vec2 end{0.0};

    // Lines: unit direction of travel, length (m), free-side normal (left of travel).
    Vec2 dir{1.0, 0.0};
    double length = 0.0;
    Vec2 normal{0.0, 1.0};

    // Arcs: centre (m), radius (m), the travelled angles as a CCW span, and whether the free side
    // is outside the circle (clockwise travel: a convex bump) or inside (a bowl).
    Vec2 center{0.0};
    double radius = 0.0;
    AngleSpan angles;
    bool free_outside = true;

    // Neighbours in the chain (-1 at the ends of an open contour).
    int prev = -1;
    int next = -1;
    int contour = 0;
    int scene_segment = 0;    // index of the scene segment (in its contour) this piece comes from
    bool smooth_end = false;  // the joint to `next` is inside one curve: G1 by construction
    int curve = -1;           // exact mode: index into Environment::curves of the curve it approximates

    // The vertex at this segment's end: a convex corner (or the end of an open chain) gets the
    // cone of free-side normals the finger may press along there. Empty width: no vertex piece.
    AngleSpan end_cone;
    // Only for the first segment of an open chain: the cone at its start.
    AngleSpan start_cone;

    Aabb box;  // bounds of the segment itself (m)
};

// Free-side unit normal of segment s at point q on it.
inline Vec2 env_normal_at(const EnvSegment& s, Vec2 q) {
    if (s.kind == EnvSegment::Kind::line) return s.normal;
    const Vec2 r = glm::normalize(q - s.center);
    return s.free_outside ? r : -r;
}

// Exact distance (m) from p to the segment.
double distance_to_segment(const EnvSegment& s, Vec2 p);

struct Environment {
    std::vector<EnvSegment> segments;
    // The scene's Bezier segments, kept exact: the proxy refines contacts on them (proxy.cpp).
    std::vector<Bezier> curves;
    AabbTree tree;
    Aabb bounds;
    // Length (m) of the shortest scene segment (a curve counts whole, not its arc pieces): the
    // scale of the thinnest feature (a wall's top), which
    // bounds how far one re-projection sub-step may move the pad (proxy.cpp).
    double min_feature = std::numeric_limits<double>::infinity();
};

// The boxes of q + rho n (outer) and q - rho n (inner) over the segment's points q and the
// free-side normals n its c-space pieces offset along, grown by 1e-10 m: what the index bounds a
// pad of radius rho (m) by (AabbTree::query_pad_reach). build_environment uses the scene's R.
OffsetBoxes offset_boxes(const EnvSegment& e, double rho);

// Compiles a validated scene (see scene_io.hpp) into an Environment.
Environment build_environment(const Scene& scene);

// True when angle a (rad) lies in span s (with `slack` rad of tolerance at both ends).
inline bool span_contains(const AngleSpan& s, double a, double slack = 0.0) {
    if (s.width >= kTwoPi) return true;
    const double rel = wrap_2pi(a - s.start);
    return rel <= s.width + slack || rel >= kTwoPi - slack;
}

// Intersection of two CCW spans: up to two pieces, written to out; returns how many.
int intersect_spans(const AngleSpan& a, const AngleSpan& b, AngleSpan out[2]);

}  // namespace contactlab
