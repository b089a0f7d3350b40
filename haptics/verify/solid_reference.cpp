// solid_reference.cpp — point-in-solid, distance and the pad's deepest point, by brute force
// (see solid_reference.hpp). Nothing here comes from the proxy, c-space or bezier code.
#include "haptics/verify/solid_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace contactlab::verify {
namespace {

constexpr int kChunkEdges = 32;             // polyline edges per pruning box
constexpr int kMaxPadEvaluations = 200000;  // a safety stop for the branch and bound

Vec2 quad_point(const QuadSegment& q, double t) {
    const double u = 1.0 - t;
    return u * u * q.p0 + 2.0 * u * t * q.p1 + t * t * q.p2;
}
Vec2 cubic_point(const CubicSegment& c, double t) {
    const double u = 1.0 - t;
    return u * u * u * c.p0 + 3.0 * u * u * t * c.p1 + 3.0 * u * t * t * c.p2 + t * t * t * c.p3;
}

// Steps for a uniform parameter walk whose chords stay within tol of a curve with |B''| <= m:
// the chord of a parameter step dt deviates by at most dt^2 m / 8.
int curve_steps(double m, double tol) {
    return std::max(1, static_cast<int>(std::ceil(std::sqrt(m / (8.0 * tol)))));
}

double distance_to_edge(Vec2 p, Vec2 a, Vec2 b) {
    const Vec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

double box_distance(Vec2 p, Vec2 lo, Vec2 hi) {
    const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x});
    const double dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
    return std::sqrt(dx * dx + dy * dy);
}

}  // namespace

void flatten_segment(const Segment& s, double tol, std::vector<Vec2>& out) {
    std::visit(
        [&](const auto& seg) {
            using T = std::decay_t<decltype(seg)>;
            if constexpr (std::is_same_v<T, LineSegment>) {
                out.push_back(seg.to);
            } else if constexpr (std::is_same_v<T, ArcSegment>) {
                // Sagitta of a chord spanning d theta: r (1 - cos(d theta / 2)) <= tol.
                const double sweep = seg.end_angle - seg.start_angle;  // rad, signed
                const double step = 2.0 * std::acos(std::max(-1.0, 1.0 - tol / seg.radius));
                const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / step)));
                for (int i = 1; i <= n; ++i)
                    out.push_back(seg.center + seg.radius * unit_at(seg.start_angle + sweep * i / n));
            } else if constexpr (std::is_same_v<T, QuadSegment>) {
                const int n = curve_steps(2.0 * glm::length(seg.p0 - 2.0 * seg.p1 + seg.p2), tol);
                for (int i = 1; i <= n; ++i) out.push_back(quad_point(seg, static_cast<double>(i) / n));
            } else {
                const double m = 6.0 * std::max(glm::length(seg.p0 - 2.0 * seg.p1 + seg.p2),
                                                glm::length(seg.p1 - 2.0 * seg.p2 + seg.p3));
                const int n = curve_steps(m, tol);
                for (int i = 1; i <= n; ++i) out.push_back(cubic_point(seg, static_cast<double>(i) / n));
            }
        },
        s);
}

SolidReference::SolidReference(const Scene& scene) {
    for (const Contour& c : scene.contours) {
        if (c.segments.empty()) continue;
        std::vector<Vec2> pts;
        pts.push_back(segment_start(c.segments.front()));
        for (const Segment& s : c.segments) flatten_segment(s, kFlattenTolerance, pts);
        if (c.closed) {
            // Shoelace: negative area is clockwise, solid inside (scene.hpp).
            double area2 = 0.0;
            for (std::size_t i = 0; i + 1 < pts.size(); ++i) area2 += cross(pts[i], pts[i + 1]);
            area2 += cross(pts.back(), pts.front());
            pts.push_back(pts.front());  // the closing edge (the contour's own)
            add_loop(pts, area2 < 0.0, static_cast<int>(pts.size()));
        } else {
            // A terrain drawn left to right: close it with a box far below (not boundary).
            const int boundary = static_cast<int>(pts.size());
            double low = pts.front().y;
            for (const Vec2& p : pts) low = std::min(low, p.y);
            low -= 1.0;  // m
            const Vec2 first = pts.front();
            pts.push_back({pts.back().x, low});
            pts.push_back({first.x, low});
            pts.push_back(first);
            add_loop(pts, true, boundary);
        }
    }
}

void SolidReference::add_loop(const std::vector<Vec2>& pts, bool solid_inside, int boundary_points) {
    Loop loop;
    loop.first = static_cast<int>(points_.size());
    loop.count = static_cast<int>(pts.size());
    loop.solid_inside = solid_inside;
    loop.first_chunk = static_cast<int>(chunks_.size());
    points_.insert(points_.end(), pts.begin(), pts.end());
    const int edges = loop.count - 1;
    for (int e = 0; e < edges; e += kChunkEdges) {
        Chunk ch;
        ch.first = loop.first + e;
        ch.count = std::min(kChunkEdges, edges - e);
        // Boundary edges are those among the first boundary_points points; a chunk mixing the
        // two kinds is split so each is one kind.
        if (e < boundary_points - 1 && e + ch.count > boundary_points - 1) ch.count = boundary_points - 1 - e;
        ch.boundary = e < boundary_points - 1;
        ch.lo = ch.hi = points_[static_cast<std::size_t>(ch.first)];
        for (int i = 1; i <= ch.count; ++i) {
            const Vec2 q = points_[static_cast<std::size_t>(ch.first + i)];
            ch.lo = glm::min(ch.lo, q);
            ch.hi = glm::max(ch.hi, q);
        }
        chunks_.push_back(ch);
        e -= kChunkEdges - ch.count;  // continue right after this chunk
    }
    loop.chunks = static_cast<int>(chunks_.size()) - loop.first_chunk;
    loop.root = build_tree(loop.first_chunk, loop.chunks);
    loops_.push_back(loop);
}

int SolidReference::build_tree(int first_chunk, int chunks) {
    Node node;
    node.first_chunk = first_chunk;
    node.chunks = chunks;
    node.lo = chunks_[static_cast<std::size_t>(first_chunk)].lo;
    node.hi = chunks_[static_cast<std::size_t>(first_chunk)].hi;
    for (int c = first_chunk + 1; c < first_chunk + chunks; ++c) {
        node.lo = glm::min(node.lo, chunks_[static_cast<std::size_t>(c)].lo);
        node.hi = glm::max(node.hi, chunks_[static_cast<std::size_t>(c)].hi);
    }
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back(node);
    if (chunks > 1) {
        const int half = chunks / 2;
        const int left = build_tree(first_chunk, half);
        const int right = build_tree(first_chunk + half, chunks - half);
        nodes_[static_cast<std::size_t>(index)].left = left;
        nodes_[static_cast<std::size_t>(index)].right = right;
    }
    return index;
}

void SolidReference::crossings(int index, Vec2 p, bool& in) const {
    const Node& node = nodes_[static_cast<std::size_t>(index)];
    if (node.lo.y > p.y || node.hi.y <= p.y || node.hi.x < p.x) return;  // no edge crosses the ray
    if (node.left >= 0) {
        crossings(node.left, p, in);
        crossings(node.right, p, in);
        return;
    }
    const Chunk& ch = chunks_[static_cast<std::size_t>(node.first_chunk)];
    for (int i = ch.first; i < ch.first + ch.count; ++i) {
        const Vec2 a = points_[static_cast<std::size_t>(i)];
        const Vec2 b = points_[static_cast<std::size_t>(i + 1)];
        if ((a.y > p.y) == (b.y > p.y)) continue;
        const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
        if (x > p.x) in = !in;
    }
}

void SolidReference::nearest(int index, Vec2 p, double& best) const {
    const Node& node = nodes_[static_cast<std::size_t>(index)];
    if (node.left >= 0) {
        // The nearer child first, so the farther one is usually pruned.
        const Node& l = nodes_[static_cast<std::size_t>(node.left)];
        const Node& r = nodes_[static_cast<std::size_t>(node.right)];
        const double dl = box_distance(p, l.lo, l.hi), dr = box_distance(p, r.lo, r.hi);
        const int first = dl <= dr ? node.left : node.right, second = dl <= dr ? node.right : node.left;
        if (std::min(dl, dr) < best) nearest(first, p, best);
        if (std::max(dl, dr) < best) nearest(second, p, best);
        return;
    }
    const Chunk& ch = chunks_[static_cast<std::size_t>(node.first_chunk)];
    if (!ch.boundary) return;
    for (int i = ch.first; i < ch.first + ch.count; ++i)
        best = std::min(best, distance_to_edge(p, points_[static_cast<std::size_t>(i)],
                                               points_[static_cast<std::size_t>(i + 1)]));
}

bool SolidReference::inside(Vec2 p) const {
    bool solid = false;
    for (const Loop& loop : loops_) {
        // Even-odd count of the edges crossing the ray from p toward +x (half-open in y, so a
        // vertex or a horizontal edge on the ray is counted consistently).
        bool in = false;
        crossings(loop.root, p, in);
        if (in == loop.solid_inside) solid = true;
    }
    return solid;
}

double SolidReference::distance_to_boundary(Vec2 p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const Loop& loop : loops_) nearest(loop.root, p, best);
    return best;
}

double SolidReference::signed_depth(Vec2 p) const {
    const double d = distance_to_boundary(p);
    return inside(p) ? d : -d;
}

SolidReference::PadDepth SolidReference::pad_depth(Vec2 center, double phi, double radius, double length,
                                                   double resolution) const {
    // Pad point at arc length a (m) from its low-angle end.
    const double theta0 = phi - 0.5 * kPi - 0.5 * length / radius;  // rad
    auto point = [&](double a) { return center + radius * unit_at(theta0 + a / radius); };
    PadDepth out;
    auto eval = [&](double a) {
        ++out.evaluations;
        return signed_depth(point(a));
    };
    // Coarse samples, then branch and bound: signed_depth is 1-Lipschitz and a chord is never
    // longer than its arc, so on [a0, a1] the depth is at most (f0 + f1 + (a1 - a0)) / 2.
    struct Interval { double a0, f0, a1, f1; };
    const int n = std::max(8, static_cast<int>(std::ceil(length / 1e-3)));
    std::vector<Interval> open;
    open.reserve(64);
    double prev_a = 0.0, prev_f = eval(0.0);
    out.depth = prev_f;
    out.at = 0.0;
    for (int i = 1; i <= n; ++i) {
        const double a = length * i / n;
        const double f = eval(a);
        if (f > out.depth) out.depth = f, out.at = a;
        open.push_back({prev_a, prev_f, a, f});
        prev_a = a;
        prev_f = f;
    }
    while (!open.empty() && out.evaluations < kMaxPadEvaluations) {
        const Interval iv = open.back();
        open.pop_back();
        if (0.5 * (iv.f0 + iv.f1 + (iv.a1 - iv.a0)) <= out.depth + resolution) continue;
        const double m = 0.5 * (iv.a0 + iv.a1);
        const double fm = eval(m);
        if (fm > out.depth) out.depth = fm, out.at = m;
        open.push_back({iv.a0, iv.f0, m, fm});
        open.push_back({m, fm, iv.a1, iv.f1});
    }
    return out;
}

}  // namespace contactlab::verify
