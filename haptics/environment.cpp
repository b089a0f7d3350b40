// environment.cpp — compiles scene contours into EnvSegments and their BVH.
#include "haptics/environment.hpp"

#include "haptics/bezier.hpp"
#include "haptics/cspace.hpp"
#include "haptics/validation.hpp"

#include <algorithm>
#include <limits>
#include <vector>

namespace contactlab {
namespace {

// Below this |sin(turn)| two segments meet tangentially (a G1 joint): no vertex piece is needed
// because the free-side normals agree there.
constexpr double kG1SinTolerance = 1e-12;

EnvSegment compile_segment(const Segment& seg, int contour) {
    EnvSegment e;
    e.contour = contour;
    e.start = segment_start(seg);
    e.end = segment_end(seg);
    if (const auto* l = std::get_if<LineSegment>(&seg)) {
        e.kind = EnvSegment::Kind::line;
        e.length = glm::length(l->to - l->from);
        e.dir = (l->to - l->from) / e.length;
        e.normal = perp_left(e.dir);  // solid on the right of travel, free on the left
        e.box.grow(e.start);
        e.box.grow(e.end);
        return e;
    }
    const auto& a = std::get<ArcSegment>(seg);
    e.kind = EnvSegment::Kind::arc;
    e.center = a.center;
    e.radius = a.radius;
    const double sweep = a.end_angle - a.start_angle;
    // Counter-clockwise travel keeps the solid on the right = outside the circle: free inside.
    e.free_outside = sweep < 0.0;
    e.angles = sweep >= 0.0 ? AngleSpan{wrap_2pi(a.start_angle), std::min(sweep, kTwoPi)}
                            : AngleSpan{wrap_2pi(a.end_angle), std::min(-sweep, kTwoPi)};
    e.length = a.radius * e.angles.width;
    e.box.grow(e.start);
    e.box.grow(e.end);
    for (int k = 0; k < 4; ++k) {  // the circle's extreme points inside the span
        const double ang = k * 0.5 * kPi;
        if (span_contains(e.angles, ang)) e.box.grow(a.center + a.radius * unit_at(ang));
    }
    return e;
}

Vec2 start_normal(const EnvSegment& s) { return env_normal_at(s, s.start); }
Vec2 end_normal(const EnvSegment& s) { return env_normal_at(s, s.end); }
Vec2 start_tangent(const EnvSegment& s) { return -perp_left(start_normal(s)); }
Vec2 end_tangent(const EnvSegment& s) { return -perp_left(end_normal(s)); }

// Cone of normals at the vertex between a (ending) and b (starting): the normal turns clockwise
// from a's to b's at a convex corner (a right turn for solid-on-the-right contours).
AngleSpan convex_cone(const EnvSegment& a, const EnvSegment& b) {
    const Vec2 t1 = end_tangent(a);
    const Vec2 t2 = start_tangent(b);
    const double turn_sin = cross(t1, t2);
    const double turn_cos = glm::dot(t1, t2);
    const bool reversal = std::abs(turn_sin) <= kG1SinTolerance && turn_cos < 0.0;
    if (turn_sin >= -kG1SinTolerance && !reversal) return {};  // concave or G1: no vertex piece
    const double from = angle_of(start_normal(b));
    const double width = reversal ? kPi : wrap_2pi(angle_of(end_normal(a)) - from);
    return {wrap_2pi(from), width};
}

// The pad radius (m) from which the segment's outer side makes no c-space piece (cspace.cpp): a
// bowl arc tighter than the pad touches only the pad's ends, and with no convex vertex at either
// end nothing else of it offsets along its normals. +inf for every other segment, and for bowls
// wider than `rho` (m), the index's pad radius: a node that holds them beside tighter ones would
// otherwise keep every outer box for that pad (AabbTree's outer_firm).
double outer_offset_limit(const EnvSegment& e, double rho) {
    const bool bowl = e.kind == EnvSegment::Kind::arc && !e.free_outside;
    if (!bowl || e.radius > rho || e.end_cone.width > 0.0 || e.start_cone.width > 0.0)
        return std::numeric_limits<double>::infinity();
    return e.radius;
}

// Validation: every c-space piece a pad of the scene's radius builds, at eight finger angles, lies
// in its segment's offset boxes (outer for the pieces the pad's outer side presses, inner for the
// concave side's), and the tree holds them. The index prunes with these boxes alone: a piece
// outside its box would be a wall the proxy cannot find. O(N); at scene load.
// A segment whose outer side the index leaves out from its limit on (outer_offset_limit) has no
// such piece at the scene's radius when that is past the limit.
void validate_index(const Environment& env, const std::vector<Aabb>& boxes, const std::vector<OffsetBoxes>& offsets,
                    const std::vector<double>& outer_limits, const FingerDef& finger) {
    if constexpr (!kValidation) return;
    CONTACTLAB_VALIDATE(env.tree.consistent(boxes), "the segment index holds every segment's boxes and cones");
    const FingerShape shape = finger_from_def(finger);
    std::vector<CPiece> pieces;
    bool inside = true;
    for (int k = 0; k < 8 && shape.radius > 0.0; ++k) {
        for (int i = 0; i < static_cast<int>(env.segments.size()); ++i) {
            pieces.clear();
            append_cspace_pieces(env, i, shape, 0.25 * kPi * k, pieces);
            const OffsetBoxes& o = offsets[static_cast<std::size_t>(i)];
            for (const CPiece& piece : pieces) {
                const Aabb b = piece_box(piece);
                const bool inner = piece.source == CPiece::Source::vertex_inner || piece.source == CPiece::Source::arc_inner;
                const Aabb& bound = inner ? o.inner : o.outer;
                if (piece.source == CPiece::Source::endpoint) continue;  // bounded by the pad's ends
                inside = inside && bound.contains(b) && (inner || shape.radius < outer_limits[static_cast<std::size_t>(i)]);
            }
        }
    }
    CONTACTLAB_VALIDATE(inside, "every segment's c-space pieces lie in its offset boxes at the scene's pad radius, "
                                "and none on the outer side past its limit");
}

// The scene's shortest segment (m): the least segment_length over its segments, the same double,
// without that length's quadrature (320 square roots, a quarter of building a seed 002 scene) for
// every curve. A quadratic curve whose direction never turns back (its control legs at less than a
// right angle) is no shorter than its chord and no longer than its control polygon, and the
// quadrature is exact to ~1e-14 there; widened by 1e-6 of themselves those bounds hold its
// computed length. Only a segment whose lower bound is no more than the least upper bound can be
// the shortest, and only those are measured.
double shortest_segment(const Scene& scene) {
    constexpr double kSlack = 1e-6;
    struct Bounds {
        const Segment* segment;
        double lo, hi;  // m
        bool exact;     // lo and hi are segment_length itself
    };
    std::vector<Bounds> all;
    double most = std::numeric_limits<double>::infinity();  // m: the shortest is no longer than this
    for (const Contour& c : scene.contours)
        for (const Segment& s : c.segments) {
            const auto* q = std::get_if<QuadSegment>(&s);
            if (q == nullptr || !(glm::dot(q->p1 - q->p0, q->p2 - q->p1) > 0.0)) {
                const double l = segment_length(s);
                all.push_back({&s, l, l, true});
            } else {
                const double chord = glm::length(q->p2 - q->p0);
                const double polygon = glm::length(q->p1 - q->p0) + glm::length(q->p2 - q->p1);
                all.push_back({&s, chord * (1.0 - kSlack), polygon * (1.0 + kSlack), false});
            }
            most = std::min(most, all.back().hi);
        }
    double shortest = std::numeric_limits<double>::infinity();
    for (const Bounds& b : all)
        if (b.lo <= most) shortest = std::min(shortest, b.exact ? b.lo : segment_length(*b.segment));
    return shortest;
}

}  // namespace

double distance_to_segment(const EnvSegment& s, Vec2 p) {
    if (s.kind == EnvSegment::Kind::line) {
        const double t = std::clamp(glm::dot(p - s.start, s.dir), 0.0, s.length);
        return glm::length(p - (s.start + t * s.dir));
    }
    const Vec2 d = p - s.center;
    if (span_contains(s.angles, angle_of(d))) return std::abs(glm::length(d) - s.radius);
    return std::min(glm::length(p - s.start), glm::length(p - s.end));
}

int intersect_spans(const AngleSpan& a, const AngleSpan& b, AngleSpan out[2]) {
    if (a.width >= kTwoPi) { out[0] = b; return b.width > 0.0 ? 1 : 0; }
    if (b.width >= kTwoPi) { out[0] = a; return a.width > 0.0 ? 1 : 0; }
    // Work relative to a.start: a = [0, wa]; b = [s, s + wb] and its copy shifted by -2 pi.
    // (Written out, not a loop over the two: the proxy's c-space asks ~4 times a tick.)
    const double s = wrap_2pi(b.start - a.start);
    int n = 0;
    const auto part = [&](double shift) {
        const double lo = std::max(0.0, shift);
        const double hi = std::min(a.width, shift + b.width);
        if (!(hi > lo)) return;
        // a.start + lo lies in [0, 4 pi): past 2 pi, one turn off is exact (Sterbenz) and is what
        // wrap_2pi's fmod returns there, without the fmod.
        double start = a.start + lo;  // rad
        if (start >= kTwoPi && start < 2.0 * kTwoPi) start -= kTwoPi;
        out[n++] = {wrap_2pi(start), hi - lo};
    };
    part(s);
    part(s - kTwoPi);
    return n;
}

// The boxes of q + rho n and q - rho n over the segment's points q and the free-side normals n its
// c-space pieces offset along (cspace.cpp): a line moved along its normal, an arc's circle grown
// or shrunk by rho (through its centre when rho exceeds its radius), and at a convex end the
// vertex's circle of radius rho over its cone. Grown by 1e-10 m against rounding: the proxy builds
// its pieces at its own radius, with its own roundings.
OffsetBoxes offset_boxes(const EnvSegment& e, double rho) {
    auto circle = [](Vec2 c, double k, double start, double width) {  // c + k u(a), a in the span
        return k >= 0.0 ? arc_bounds(c, k, start, width) : arc_bounds(c, -k, start + kPi, width);
    };
    OffsetBoxes b;
    if (e.kind == EnvSegment::Kind::line) {
        for (const double side : {1.0, -1.0}) {
            Aabb& box = side > 0.0 ? b.outer : b.inner;
            box.grow(e.start + side * rho * e.normal);
            box.grow(e.end + side * rho * e.normal);
        }
    } else {
        const double out = e.free_outside ? rho : -rho;  // m: q + rho n = c + (radius + out) u
        b.outer = circle(e.center, e.radius + out, e.angles.start, e.angles.width);
        b.inner = circle(e.center, e.radius - out, e.angles.start, e.angles.width);
    }
    auto vertex = [&](Vec2 v, const AngleSpan& cone) {
        if (cone.width <= 0.0) return;
        b.outer.grow(arc_bounds(v, rho, cone.start, cone.width));
        b.inner.grow(arc_bounds(v, rho, cone.start + kPi, cone.width));
    };
    vertex(e.end, e.end_cone);
    if (e.prev < 0) vertex(e.start, e.start_cone);
    constexpr double kRounding = 1e-10;  // m
    return {b.outer.grown(kRounding), b.inner.grown(kRounding)};
}

Environment build_environment(const Scene& scene) {
    Environment env;
    env.min_feature = shortest_segment(scene);
    std::vector<CurvePiece> curve_pieces;
    for (int c = 0; c < static_cast<int>(scene.contours.size()); ++c) {
        const Contour& contour = scene.contours[c];
        const int first = static_cast<int>(env.segments.size());
        for (int k = 0; k < static_cast<int>(contour.segments.size()); ++k) {
            const Segment& s = contour.segments[k];
            if (!segment_is_curve(s)) {
                env.segments.push_back(compile_segment(s, c));
                env.segments.back().scene_segment = k;
                continue;
            }
            // A curve becomes a G1 chain of arcs (exact mode) or chords (flatten mode).
            curve_pieces.clear();
            const Bezier b = segment_bezier(s);
            const int curve_index = static_cast<int>(env.curves.size());
            env.curves.push_back(b);
            if (scene.curves.mode == CurveMode::exact) {
                bezier_to_arcs(b, kExactCurveTolerance, curve_pieces);
            } else {
                bezier_to_lines(b, scene.curves.tolerance, curve_pieces);
            }
            for (std::size_t i = 0; i < curve_pieces.size(); ++i) {
                const CurvePiece& p = curve_pieces[i];
                const Segment piece = p.is_arc ? Segment{ArcSegment{p.center, p.radius, p.start_angle, p.end_angle}}
                                               : Segment{LineSegment{p.from, p.to}};
                env.segments.push_back(compile_segment(piece, c));
                env.segments.back().scene_segment = k;
                // Exact mode only: the proxy refines contacts on the true curve. Flatten mode is the
                // user's chosen approximation and stays as flattened.
                if (scene.curves.mode == CurveMode::exact) env.segments.back().curve = curve_index;
                // Inside an exact curve the joints are smooth by construction: rounding must not
                // turn them into tiny vertices.
                env.segments.back().smooth_end =
                    scene.curves.mode == CurveMode::exact && i + 1 < curve_pieces.size() && !p.corner_after;
            }
        }
        const int count = static_cast<int>(env.segments.size()) - first;
        for (int i = 0; i < count; ++i) {
            EnvSegment& e = env.segments[first + i];
            const bool last = i + 1 == count;
            e.prev = i > 0 ? first + i - 1 : (contour.closed ? first + count - 1 : -1);
            e.next = !last ? first + i + 1 : (contour.closed ? first : -1);
        }
        for (int i = 0; i < count; ++i) {
            EnvSegment& e = env.segments[first + i];
            if (e.smooth_end) {
                e.end_cone = {};
            } else if (e.next >= 0) {
                e.end_cone = convex_cone(e, env.segments[e.next]);
            } else {
                // Open end: the profile is capped as if a cliff fell away into the solid, so the
                // normal turns a quarter turn clockwise from the segment's normal to its tangent.
                e.end_cone = {wrap_2pi(angle_of(end_tangent(e))), 0.5 * kPi};
            }
            if (e.prev < 0) e.start_cone = {wrap_2pi(angle_of(start_normal(e))), 0.5 * kPi};
        }
    }
    std::vector<Aabb> boxes;
    std::vector<NormalCone> normals;  // free-side normals a c-space piece of the segment offsets along
    std::vector<OffsetBoxes> offsets;  // the segment's offsets at the scene's pad radius
    std::vector<double> outer_limits;  // m: the pad radius from which the outer offset makes no piece
    boxes.reserve(env.segments.size());
    outer_limits.reserve(env.segments.size());
    normals.reserve(env.segments.size());
    offsets.reserve(env.segments.size());
    const double rho = std::max(scene.finger.radius, 0.0);  // m
    for (const EnvSegment& e : env.segments) {
        boxes.push_back(e.box);
        env.bounds.grow(e.box);
        NormalCone cone;
        if (e.kind == EnvSegment::Kind::line) {
            cone = {wrap_2pi(angle_of(e.normal)), 0.0};
        } else {
            // Radial normals over the travelled angles: outward on a bump, inward in a bowl.
            cone = {wrap_2pi(e.angles.start + (e.free_outside ? 0.0 : kPi)), e.angles.width};
        }
        // The vertex circles at the segment's convex ends offset along their cones of normals.
        if (e.end_cone.width > 0.0) cone = merge_cones(cone, {e.end_cone.start, e.end_cone.width});
        if (e.prev < 0 && e.start_cone.width > 0.0) cone = merge_cones(cone, {e.start_cone.start, e.start_cone.width});
        normals.push_back(cone);
        offsets.push_back(offset_boxes(e, rho));
        outer_limits.push_back(outer_offset_limit(e, rho));
    }
    env.tree = AabbTree(boxes, normals, offsets, rho, outer_limits);
    validate_index(env, boxes, offsets, outer_limits, scene.finger);
    return env;
}

}  // namespace contactlab
