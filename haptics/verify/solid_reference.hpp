// solid_reference.hpp — an independent answer to "is the pad inside a solid, and how deep?".
//
// The proxy (proxy.cpp) works in configuration space with offset pieces, pad-end copies, vertex
// circles and arc splines of curves. This reference shares none of that: it flattens every scene
// segment into a dense polyline straight from the scene's own definitions (lines, arcs, quadratic
// and cubic Beziers evaluated here, not through bezier.hpp), decides point-in-solid by counting
// crossings, measures the distance to that polyline, and searches the pad arc for its deepest
// point by branch and bound. It is slow (tens of microseconds a query) and meant for tests and the
// `contactlab fuzz-contact` soak, never for the servo.
//
// The solid (scene.hpp's convention): a closed contour drawn clockwise is solid inside, drawn
// counter-clockwise solid outside (a cavity). An open chain is a terrain: solid on the right of
// travel, which the reference closes with a box far below the chain (from its end straight down,
// back under it, up to its start). That closure is only right for chains drawn left to right
// (solid below) and for pads kept away from the chain's two ends: random_contact_scenes.hpp
// generates exactly those, and the closure's sides are not counted as boundary.
//
// Accuracy: the polyline is within kFlattenTolerance of the true contour, so inside-ness is exact
// for points deeper than that and depths are within it.
#pragma once

#include "haptics/scene.hpp"
#include "haptics/vec2.hpp"

#include <vector>

namespace contactlab::verify {

// m: every flattened chord lies within this of its segment.
inline constexpr double kFlattenTolerance = 5e-9;

class SolidReference {
public:
    explicit SolidReference(const Scene& scene);

    // Signed depth (m) of p: the distance to the contour, positive inside a solid, negative outside.
    // 1-Lipschitz in p, which the pad search relies on.
    double signed_depth(Vec2 p) const;
    bool inside(Vec2 p) const;
    double distance_to_boundary(Vec2 p) const;  // m

    // The pad of a finger with centre `center` (m), angle phi (rad), radius R and length L (m):
    // the largest signed depth of any pad point (m), found to within `resolution` (m). Also
    // returns the arc length (m from the pad's low-angle end) where it occurs.
    struct PadDepth {
        double depth = 0.0;  // m, max over the pad of signed_depth (negative: the pad is clear)
        double at = 0.0;     // m along the pad from its low-angle end
        int evaluations = 0;
    };
    PadDepth pad_depth(Vec2 center, double phi, double radius, double length, double resolution) const;

private:
    struct Chunk {  // a run of polyline edges with their bounding box, for pruning
        int first = 0, count = 0;  // edges [first, first + count) of points_ (edge i: i -> i + 1)
        Vec2 lo{0.0}, hi{0.0};
        bool boundary = true;       // false for an open chain's closing box (not the contour)
    };
    struct Node {  // a box over chunks [first_chunk, first_chunk + chunks); leaf when chunks == 1
        Vec2 lo{0.0}, hi{0.0};
        int first_chunk = 0, chunks = 0;
        int left = -1, right = -1;  // children in nodes_
    };
    struct Loop {  // one closed polygon of the crossing test
        int first = 0, count = 0;   // points_[first, first + count), closed back to first
        bool solid_inside = true;   // clockwise: solid inside; counter-clockwise: a cavity
        int first_chunk = 0, chunks = 0;
        int root = -1;              // its box tree in nodes_ (consecutive chunks are neighbours)
    };
    void add_loop(const std::vector<Vec2>& pts, bool solid_inside, int boundary_points);
    int build_tree(int first_chunk, int chunks);
    void crossings(int node, Vec2 p, bool& in) const;
    void nearest(int node, Vec2 p, double& best) const;

    std::vector<Vec2> points_;
    std::vector<Chunk> chunks_;
    std::vector<Loop> loops_;
    std::vector<Node> nodes_;
};

// Appends points along one scene segment (its start excluded, its end included), every chord
// within `tolerance` (m) of the segment. Exposed for the generator's overlap check.
void flatten_segment(const Segment& s, double tolerance, std::vector<Vec2>& out);

}  // namespace contactlab::verify
