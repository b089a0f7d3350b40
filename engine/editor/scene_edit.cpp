// scene_edit.cpp — handles, picking and edits (see scene_edit.hpp).
#include "engine/editor/scene_edit.hpp"

#include <algorithm>
#include <cmath>

#include "haptics/scene_io.hpp"  // kSceneJoinTolerance

namespace contactlab::editor {
namespace {

Vec2* point_ref(Segment& s, int i) {
    if (auto* l = std::get_if<LineSegment>(&s)) return i == 0 ? &l->from : i == 1 ? &l->to : nullptr;
    if (auto* q = std::get_if<QuadSegment>(&s)) return i == 0 ? &q->p0 : i == 1 ? &q->p1 : i == 2 ? &q->p2 : nullptr;
    if (auto* c = std::get_if<CubicSegment>(&s))
        return i == 0 ? &c->p0 : i == 1 ? &c->p1 : i == 2 ? &c->p2 : i == 3 ? &c->p3 : nullptr;
    return nullptr;  // arcs
}

Segment reversed(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return LineSegment{l->to, l->from};
    if (auto* q = std::get_if<QuadSegment>(&s)) return QuadSegment{q->p2, q->p1, q->p0};
    if (auto* c = std::get_if<CubicSegment>(&s)) return CubicSegment{c->p3, c->p2, c->p1, c->p0};
    const auto& a = std::get<ArcSegment>(s);
    return ArcSegment{a.center, a.radius, a.end_angle, a.start_angle};
}

// An arc's three handles: start, the point halfway along, end (m).
Vec2 arc_mid(const ArcSegment& a) {
    const double m = 0.5 * (a.start_angle + a.end_angle);
    return a.center + a.radius * Vec2(std::cos(m), std::sin(m));
}

// The segment with point i moved to p. An arc is refitted through its three handles with one of
// them moved (unchanged when they fall in a line: no circle passes through them).
Segment with_point(const Segment& s, int i, Vec2 p) {
    if (const auto* a = std::get_if<ArcSegment>(&s)) {
        Vec2 q[3] = {segment_start(s), arc_mid(*a), segment_end(s)};
        q[i] = p;
        if (const auto fit = arc_through(q[0], q[1], q[2])) return *fit;
        return s;
    }
    Segment out = s;
    if (Vec2* r = point_ref(out, i)) *r = p;
    return out;
}

// Moves a segment's first / last point (arcs: their end is already where it must be, to rounding).
void set_start(Segment& s, Vec2 p) {
    if (Vec2* q = point_ref(s, 0)) *q = p;
}
void set_end(Segment& s, Vec2 p) {
    if (Vec2* q = point_ref(s, handle_count(s) - 1)) *q = p;
}

}  // namespace

bool valid_handle(const Scene& scene, const Handle& h) {
    return h.contour >= 0 && h.contour < static_cast<int>(scene.contours.size()) && h.segment >= 0 &&
           h.segment < static_cast<int>(scene.contours[h.contour].segments.size()) && h.point >= 0 &&
           h.point < handle_count(scene.contours[h.contour].segments[h.segment]);
}

int handle_count(const Segment& s) {
    if (std::holds_alternative<LineSegment>(s)) return 2;
    if (std::holds_alternative<QuadSegment>(s) || std::holds_alternative<ArcSegment>(s)) return 3;
    if (std::holds_alternative<CubicSegment>(s)) return 4;
    return 0;
}

Vec2 handle_position(const Scene& scene, const Handle& h) {
    if (!valid_handle(scene, h)) return Vec2{0.0};
    Segment s = scene.contours[h.contour].segments[h.segment];
    if (const auto* a = std::get_if<ArcSegment>(&s)) return h.point == 0 ? segment_start(s) : h.point == 1 ? arc_mid(*a) : segment_end(s);
    return *point_ref(s, h.point);
}

bool handle_is_end(const Scene& scene, const Handle& h) {
    if (!valid_handle(scene, h)) return false;
    return h.point == 0 || h.point == handle_count(scene.contours[h.contour].segments[h.segment]) - 1;
}

std::optional<Handle> pick_handle(const Scene& scene, Vec2 p, double radius) {
    std::optional<Handle> best;
    double best_d = radius;
    bool best_end = false;
    for (int c = 0; c < static_cast<int>(scene.contours.size()); ++c) {
        const auto& segs = scene.contours[c].segments;
        for (int s = 0; s < static_cast<int>(segs.size()); ++s) {
            const int n = handle_count(segs[s]);
            for (int i = 0; i < n; ++i) {
                const Handle h{c, s, i};
                const double d = glm::length(handle_position(scene, h) - p);
                const bool end = i == 0 || i == n - 1;
                if (d < best_d || (d <= best_d && end && !best_end && best)) {
                    best = h;
                    best_d = d;
                    best_end = end;
                }
            }
        }
    }
    return best;
}

std::optional<Handle> pick_open_end(const Scene& scene, Vec2 p, double radius) {
    std::optional<Handle> best;
    double best_d = radius;
    for (int c = 0; c < static_cast<int>(scene.contours.size()); ++c) {
        const Contour& k = scene.contours[c];
        if (k.closed || k.segments.empty()) continue;
        const int last = static_cast<int>(k.segments.size()) - 1;
        const double d_end = glm::length(segment_end(k.segments[last]) - p);
        const double d_start = glm::length(segment_start(k.segments[0]) - p);
        if (d_end <= best_d) {
            best = Handle{c, last, std::max(0, handle_count(k.segments[last]) - 1)};
            best_d = d_end;
        }
        if (d_start < best_d) {
            best = Handle{c, 0, 0};
            best_d = d_start;
        }
    }
    return best;
}

Scene move_handle(const Scene& scene, const Handle& h, Vec2 to) {
    Scene out = scene;
    if (!valid_handle(scene, h)) return out;
    Contour& k = out.contours[h.contour];
    const int n = static_cast<int>(k.segments.size());
    Segment& seg = k.segments[h.segment];
    if (const auto* a = std::get_if<ArcSegment>(&seg)) {
        // Refitted through its three handles with this one moved; no circle through three points
        // in a line: the edit is refused (the scene comes back unchanged).
        Vec2 q[3] = {segment_start(seg), arc_mid(*a), segment_end(seg)};
        q[h.point] = to;
        const auto fit = arc_through(q[0], q[1], q[2]);
        if (!fit) return scene;
        seg = *fit;
    } else {
        seg = with_point(seg, h.point, to);
    }
    const int last = handle_count(seg) - 1;
    // Joined neighbour: the previous segment's end (for point 0) or the next one's start; the
    // moved segment's own end point (an arc's is recomputed) is what they join.
    if (h.point == 0 && (h.segment > 0 || k.closed)) {
        Segment& prev = k.segments[(h.segment + n - 1) % n];
        prev = with_point(prev, handle_count(prev) - 1, segment_start(seg));
    } else if (h.point == last && (h.segment < n - 1 || k.closed)) {
        Segment& next = k.segments[(h.segment + 1) % n];
        next = with_point(next, 0, segment_end(seg));
    }
    return out;
}

Scene add_line(const Scene& scene, Vec2 a, Vec2 b, double join_radius) {
    return add_segment(scene, LineSegment{a, b}, join_radius);
}

Scene add_segment(const Scene& scene, const Segment& segment, double join_radius) {
    Scene out = scene;
    const Vec2 a = segment_start(segment);
    if (const auto end = pick_open_end(scene, a, join_radius)) {
        Contour& k = out.contours[end->contour];
        if (end->segment == static_cast<int>(k.segments.size()) - 1 && end->point > 0) {
            Segment seg = segment;
            set_start(seg, segment_end(k.segments.back()));  // exact join
            k.segments.push_back(seg);
        } else if (end->segment == 0 && end->point == 0) {
            Segment seg = reversed(segment);  // keep the chain's direction (and solid side)
            set_end(seg, segment_start(k.segments.front()));
            k.segments.insert(k.segments.begin(), seg);
        }
        // Back at the chain's other end: the contour closes (drawn clockwise it is solid inside).
        if (k.segments.size() >= 2 && glm::length(segment_end(k.segments.back()) - segment_start(k.segments.front())) <=
                                          kSceneJoinTolerance) {
            set_end(k.segments.back(), segment_start(k.segments.front()));
            k.closed = k.segments.size() >= 3 || !std::holds_alternative<LineSegment>(k.segments.back());
        }
        return out;
    }
    Contour c;
    c.closed = false;
    c.segments.push_back(segment);
    out.contours.push_back(std::move(c));
    return out;
}

std::optional<ArcSegment> arc_through(Vec2 a, Vec2 m, Vec2 b) {
    // Circumcentre of the triangle a, m, b.
    const Vec2 ab = b - a, am = m - a;
    const double d = 2.0 * (am.x * ab.y - am.y * ab.x);
    const double scale = std::max(glm::length(ab), glm::length(am));
    if (!(scale > 0.0) || std::abs(d) < 1e-9 * scale * scale) return std::nullopt;
    const double am2 = glm::dot(am, am), ab2 = glm::dot(ab, ab);
    const Vec2 c = a + Vec2(ab.y * am2 - am.y * ab2, am.x * ab2 - ab.x * am2) / d;
    ArcSegment arc;
    arc.center = c;
    arc.radius = glm::length(a - c);
    const double a0 = std::atan2(a.y - c.y, a.x - c.x);
    const auto ccw_from_a0 = [&](Vec2 p) {
        double t = std::atan2(p.y - c.y, p.x - c.x) - a0;
        while (t < 0.0) t += 2.0 * kPi;
        while (t >= 2.0 * kPi) t -= 2.0 * kPi;
        return t;
    };
    const double to_b = ccw_from_a0(b), to_m = ccw_from_a0(m);
    arc.start_angle = a0;
    // Counter-clockwise if m lies on the way from a to b going that way, else clockwise.
    arc.end_angle = to_m < to_b ? a0 + to_b : a0 - (2.0 * kPi - to_b);
    return arc;
}

std::optional<Vec2> continuation_tangent(const Scene& scene, Vec2 p, double radius) {
    const auto end = pick_open_end(scene, p, radius);
    if (!end) return std::nullopt;
    const auto& segs = scene.contours[end->contour].segments;
    // At the chain's last point: on along its end tangent. At its first point the new segment is
    // prepended reversed, so it must leave against the chain's start tangent.
    if (end->segment == static_cast<int>(segs.size()) - 1 && end->point > 0) return segment_end_tangent(segs.back());
    return -segment_start_tangent(segs.front());
}

Vec2 project_on_ray(Vec2 origin, Vec2 dir, Vec2 p) {
    return origin + dir * std::max(0.0, glm::dot(p - origin, dir));
}

Vec2 project_on_normal(Vec2 origin, Vec2 dir, Vec2 p) {
    const Vec2 n(-dir.y, dir.x);
    return origin + n * glm::dot(p - origin, n);
}

namespace {

// The arc about c from `start` to the angle of `end`, turning counter-clockwise (dir > 0) or
// clockwise (dir < 0); the end lies on the circle through start.
ArcSegment arc_about(Vec2 c, Vec2 start, Vec2 end, int dir) {
    ArcSegment a;
    a.center = c;
    a.radius = glm::length(start - c);
    a.start_angle = std::atan2(start.y - c.y, start.x - c.x);
    double sweep = std::atan2(end.y - c.y, end.x - c.x) - a.start_angle;  // rad
    while (sweep <= 0.0) sweep += 2.0 * kPi;
    while (sweep > 2.0 * kPi) sweep -= 2.0 * kPi;
    a.end_angle = dir > 0 ? a.start_angle + sweep : a.start_angle - (2.0 * kPi - sweep);
    return a;
}

}  // namespace

std::optional<ArcSegment> arc_center_radius(Vec2 start, Vec2 center, Vec2 end, int dir) {
    const double r = glm::length(start - center);
    if (!(r > 1e-9) || !(glm::length(end - center) > 1e-9)) return std::nullopt;
    if (dir == 0) {
        // The short way round (|sweep| <= pi).
        const Vec2 a = start - center, b = end - center;
        dir = a.x * b.y - a.y * b.x >= 0.0 ? 1 : -1;
    }
    ArcSegment arc = arc_about(center, start, end, dir);
    if (std::abs(arc.end_angle - arc.start_angle) < 1e-9) return std::nullopt;  // start == end
    return arc;
}

std::optional<ArcSegment> tangent_arc_through(Vec2 start, Vec2 tangent, Vec2 through, Vec2 end) {
    const Vec2 n(-tangent.y, tangent.x);  // left normal
    const Vec2 m = through - start;
    const double mn = glm::dot(m, n);
    if (std::abs(mn) < 1e-9 * std::max(1e-12, glm::dot(m, m))) return std::nullopt;  // on the tangent line
    // The circle tangent to `tangent` at start through m: centre start + r n, |m - r n| = |r|.
    const double r = glm::dot(m, m) / (2.0 * mn);  // m, signed: > 0 centre on the left
    const Vec2 c = start + r * n;
    if (!(glm::length(end - c) > 1e-9)) return std::nullopt;
    return arc_about(c, start, end, r > 0.0 ? 1 : -1);
}

Scene delete_segment(const Scene& scene, int contour, int segment) {
    Scene out = scene;
    if (contour < 0 || contour >= static_cast<int>(out.contours.size())) return out;
    Contour& k = out.contours[contour];
    const int n = static_cast<int>(k.segments.size());
    if (segment < 0 || segment >= n) return out;
    if (k.closed) {
        // Rotate so the chain starts after the removed segment, then open it.
        std::vector<Segment> segs;
        for (int i = 1; i < n; ++i) segs.push_back(k.segments[(segment + i) % n]);
        k.segments = std::move(segs);
        k.closed = false;
    } else if (segment == 0 || segment == n - 1) {
        k.segments.erase(k.segments.begin() + segment);
    } else {
        Contour tail;
        tail.closed = false;
        tail.segments.assign(k.segments.begin() + segment + 1, k.segments.end());
        k.segments.erase(k.segments.begin() + segment, k.segments.end());
        out.contours.insert(out.contours.begin() + contour + 1, std::move(tail));
    }
    out.contours.erase(std::remove_if(out.contours.begin(), out.contours.end(),
                                      [](const Contour& c) { return c.segments.empty(); }),
                       out.contours.end());
    return out;
}

Scene reverse_contour(const Scene& scene, int contour) {
    Scene out = scene;
    if (contour < 0 || contour >= static_cast<int>(out.contours.size())) return out;
    auto& segs = out.contours[contour].segments;
    std::reverse(segs.begin(), segs.end());
    for (Segment& s : segs) s = reversed(s);
    return out;
}

Scene toggle_closed(const Scene& scene, int contour) {
    Scene out = scene;
    if (contour < 0 || contour >= static_cast<int>(out.contours.size())) return out;
    Contour& c = out.contours[contour];
    if (c.segments.empty()) return out;
    if (!c.closed) {
        const Vec2 first = segment_start(c.segments.front()), last = segment_end(c.segments.back());
        if (glm::length(first - last) > kSceneJoinTolerance) c.segments.push_back(LineSegment{last, first});
    }
    c.closed = !c.closed;
    return out;
}

int segment_count(const Scene& scene) {
    int n = 0;
    for (const Contour& c : scene.contours) n += static_cast<int>(c.segments.size());
    return n;
}

}  // namespace contactlab::editor
