// contour_crossing.cpp — crossings of closed contours (see contour_crossing.hpp for the rule).
//
// Index
//   [SECTION] Pieces          closed contours as a chain of lines and arcs (curves on chords)
//   [SECTION] Intersections   line/line, line/circle, circle/circle, with tangencies snapped
//   [SECTION] Branches        the two directions each side leaves a meeting point along
//   [SECTION] Search          the box tree and the first crossing in piece order
#include "haptics/contour_crossing.hpp"

#include "haptics/aabb_tree.hpp"
#include "haptics/bezier.hpp"
#include "haptics/environment.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace contactlab {
namespace {

constexpr double kEps = kCrossingPointTolerance;  // m
// rad: directions nearer than this are tied (tangent branches); the curvature then decides.
constexpr double kAngleTie = 1e-9;

//-------------------------------------------------------------------------------------------------
// [SECTION] Pieces
//-------------------------------------------------------------------------------------------------

struct Piece {
    CurvePiece g;       // a line (from, to) or an arc (centre, radius, start_angle -> end_angle)
    AngleSpan span;     // arcs: the travelled angles as a CCW span
    double turn = 1.0;  // arcs: +1 travelled counter-clockwise, -1 clockwise
    int contour = 0;
    int segment = 0;
    int prev = 0, next = 0;  // neighbours in the closed chain (piece indices)
};

Piece arc_piece(const ArcSegment& a) {
    Piece p;
    p.g.is_arc = true;
    p.g.center = a.center;
    p.g.radius = a.radius;
    p.g.start_angle = a.start_angle;
    p.g.end_angle = a.end_angle;
    p.g.from = segment_start(Segment{a});
    p.g.to = segment_end(Segment{a});
    const double sweep = a.end_angle - a.start_angle;
    p.turn = sweep >= 0.0 ? 1.0 : -1.0;
    p.span = sweep >= 0.0 ? AngleSpan{wrap_2pi(a.start_angle), std::min(sweep, kTwoPi)}
                          : AngleSpan{wrap_2pi(a.end_angle), std::min(-sweep, kTwoPi)};
    return p;
}

Piece line_piece(Vec2 from, Vec2 to) {
    Piece p;
    p.g.from = from;
    p.g.to = to;
    return p;
}

// The closed contours' pieces in order (contour, segment, chord), each chain linked in a ring.
std::vector<Piece> closed_pieces(const std::vector<Contour>& contours) {
    std::vector<Piece> out;
    std::vector<CurvePiece> chords;
    for (std::size_t c = 0; c < contours.size(); ++c) {
        if (!contours[c].closed || contours[c].segments.empty()) continue;
        const std::size_t first = out.size();
        for (std::size_t s = 0; s < contours[c].segments.size(); ++s) {
            const Segment& seg = contours[c].segments[s];
            const std::size_t before = out.size();
            if (const auto* l = std::get_if<LineSegment>(&seg)) {
                out.push_back(line_piece(l->from, l->to));
            } else if (const auto* a = std::get_if<ArcSegment>(&seg)) {
                out.push_back(arc_piece(*a));
            } else {
                // Beyond 1 m the tolerance grows with the curve: chords then number about the
                // same as for a metre-long curve of the same shape, not millions (a file may
                // hold curves 1e6 m long).
                const Bezier b = segment_bezier(seg);
                Aabb hull;
                for (int k = 0; k <= b.degree; ++k) hull.grow(b.p[k]);
                const double size = std::max(hull.hi.x - hull.lo.x, hull.hi.y - hull.lo.y);  // m
                chords.clear();
                bezier_to_lines(b, kCrossingCurveTolerance * std::max(1.0, size), chords);
                for (const CurvePiece& k : chords) out.push_back(line_piece(k.from, k.to));
            }
            for (std::size_t i = before; i < out.size(); ++i) {
                out[i].contour = static_cast<int>(c);
                out[i].segment = static_cast<int>(s);
            }
        }
        const int n = static_cast<int>(out.size() - first), base = static_cast<int>(first);
        for (int i = 0; i < n; ++i) {
            out[first + i].prev = base + (i + n - 1) % n;
            out[first + i].next = base + (i + 1) % n;
        }
    }
    return out;
}

Aabb piece_box(const Piece& p) {
    if (!p.g.is_arc) {
        Aabb b;
        b.grow(p.g.from);
        b.grow(p.g.to);
        return b;
    }
    return arc_bounds(p.g.center, p.g.radius, p.span.start, p.span.width);
}

// Unit direction of travel at x (on the piece) and the curvature (1/m, > 0 bending left).
Vec2 tangent_at(const Piece& p, Vec2 x) {
    if (!p.g.is_arc) return glm::normalize(p.g.to - p.g.from);
    return p.turn * perp_left(glm::normalize(x - p.g.center));
}
double curvature(const Piece& p) { return p.g.is_arc ? p.turn / p.g.radius : 0.0; }

// Whether x, found on the piece's line or circle, lies on the piece (or within kEps of its ends).
bool on_piece(const Piece& p, Vec2 x) {
    if (glm::length(x - p.g.from) <= kEps || glm::length(x - p.g.to) <= kEps) return true;
    if (!p.g.is_arc) {
        const Vec2 d = p.g.to - p.g.from;
        const double s = glm::dot(x - p.g.from, d) / glm::dot(d, d);
        return s >= 0.0 && s <= 1.0;
    }
    return span_contains(p.span, angle_of(x - p.g.center));
}

//-------------------------------------------------------------------------------------------------
// [SECTION] Intersections
//-------------------------------------------------------------------------------------------------

// Below this half-chord (m) a line or circle meeting a circle is tangent to it: the rounding of
// the roots, sqrt(2 r eps S) for coordinates of size S, would otherwise split one tangent point
// into two crossings a hair apart. A real crossing that cuts off less is read as a touch.
double tangent_tolerance(double r, double scale) { return 8.0 * std::sqrt(DBL_EPSILON * r * scale); }

int line_line(const Piece& a, const Piece& b, Vec2 out[2]) {
    const Vec2 d = a.g.to - a.g.from, e = b.g.to - b.g.from;
    const double den = cross(d, e);
    // Parallel: apart, or along each other (a touch; where they part is a vertex of one of them).
    if (std::abs(den) <= 1e-14 * glm::length(d) * glm::length(e)) return 0;
    out[0] = a.g.from + (cross(b.g.from - a.g.from, e) / den) * d;
    return 1;
}

int line_circle(const Piece& l, Vec2 c, double r, Vec2 out[2]) {
    const Vec2 d = l.g.to - l.g.from;
    const Vec2 u = d / glm::length(d);
    const Vec2 foot = l.g.from + glm::dot(c - l.g.from, u) * u;
    const double dist = glm::length(c - foot);
    if (dist > r + kEps) return 0;
    const double h2 = (r - dist) * (r + dist);
    const double h = h2 > 0.0 ? std::sqrt(h2) : 0.0;
    const double scale = std::max({r, std::abs(c.x), std::abs(c.y), std::abs(l.g.from.x), std::abs(l.g.from.y),
                                   std::abs(l.g.to.x), std::abs(l.g.to.y)});
    if (h <= tangent_tolerance(r, scale)) {
        out[0] = foot;
        return 1;
    }
    out[0] = foot - h * u;
    out[1] = foot + h * u;
    return 2;
}

int circle_circle(Vec2 c0, double r0, Vec2 c1, double r1, Vec2 out[2]) {
    const Vec2 v = c1 - c0;
    const double d = glm::length(v);
    // Concentric: apart, or the same circle (along each other: a touch).
    if (d <= 0.0 || d > r0 + r1 + kEps || d < std::abs(r0 - r1) - kEps) return 0;
    const double a = (d * d + r0 * r0 - r1 * r1) / (2.0 * d);  // m from c0 along v
    const double h2 = (r0 - a) * (r0 + a);
    const double h = h2 > 0.0 ? std::sqrt(h2) : 0.0;
    const Vec2 u = v / d, m = c0 + a * u;
    // a's rounding grows as S^2 / d for nearly concentric circles.
    const double size = std::max({r0, r1, std::abs(c0.x), std::abs(c0.y), std::abs(c1.x), std::abs(c1.y)});
    if (h <= tangent_tolerance(r0, size * std::max(1.0, size / d))) {
        out[0] = m;
        return 1;
    }
    out[0] = m + h * perp_left(u);
    out[1] = m - h * perp_left(u);
    return 2;
}

// Points where the two pieces' lines or circles meet that lie on both pieces.
int intersections(const Piece& a, const Piece& b, Vec2 out[2]) {
    Vec2 x[2];
    int n = 0;
    if (!a.g.is_arc && !b.g.is_arc) n = line_line(a, b, x);
    else if (!a.g.is_arc) n = line_circle(a, b.g.center, b.g.radius, x);
    else if (!b.g.is_arc) n = line_circle(b, a.g.center, a.g.radius, x);
    else n = circle_circle(a.g.center, a.g.radius, b.g.center, b.g.radius, x);
    int kept = 0;
    for (int i = 0; i < n; ++i)
        if (on_piece(a, x[i]) && on_piece(b, x[i])) out[kept++] = x[i];
    return kept;
}

//-------------------------------------------------------------------------------------------------
// [SECTION] Branches
//-------------------------------------------------------------------------------------------------

// A direction leaving the meeting point: its angle (rad) and the curvature of its path (1/m,
// > 0 bending counter-clockwise), which orders directions that tie.
struct Ray {
    double angle = 0.0;
    double curvature = 0.0;
};

Ray ray(Vec2 t, double k) { return {angle_of(t), k}; }

// A side of a meeting: a piece passing through the point (interior) or the joint after a piece.
struct Branch {
    int piece = 0;
    bool joint = false;
    bool operator==(const Branch&) const = default;
};

void rays_of(const std::vector<Piece>& pieces, const Branch& b, Vec2 x, Ray out[2]) {
    const Piece& p = pieces[static_cast<std::size_t>(b.piece)];
    if (!b.joint) {
        const Vec2 t = tangent_at(p, x);
        out[0] = ray(t, curvature(p));
        out[1] = ray(-t, -curvature(p));
        return;
    }
    const Piece& q = pieces[static_cast<std::size_t>(p.next)];
    out[0] = ray(-tangent_at(p, p.g.to), -curvature(p));  // back along p
    out[1] = ray(tangent_at(q, q.g.from), curvature(q));   // on along the next piece
}

int compare_curvature(double k1, double k2) {
    const double tie = 1e-9 * std::max(std::abs(k1), std::abs(k2)) + 1e-12;  // 1/m
    if (std::abs(k1 - k2) <= tie) return 0;
    return k1 < k2 ? -1 : 1;
}

// Position of r counter-clockwise from `base`: (angle in [0, 2 pi], curvature). A ray tied in
// angle with the base lies just after it when it bends further left, just before it (2 pi) when
// less; none when it ties in curvature too (the same path: undecided).
struct Key {
    double angle = 0.0;
    double curvature = 0.0;
    bool tied_with_base = false;
};

Key key_of(const Ray& r, const Ray& base) {
    double phi = wrap_2pi(r.angle - base.angle);
    if (phi >= kTwoPi - kAngleTie) phi -= kTwoPi;
    if (std::abs(phi) <= kAngleTie) {
        const int c = compare_curvature(r.curvature, base.curvature);
        if (c == 0) return {0.0, r.curvature, true};
        phi = c > 0 ? 0.0 : kTwoPi;
    }
    return {phi, r.curvature, false};
}

// -1, 0 (tied: same direction and curvature), +1.
int compare(const Key& a, const Key& b) {
    if (std::abs(a.angle - b.angle) > kAngleTie) return a.angle < b.angle ? -1 : 1;
    return compare_curvature(a.curvature, b.curvature);
}

// True when B's two directions lie strictly on either side of A's two: the branches pass
// through each other. Any tie (a shared direction) is a touch.
bool separates(const Ray a[2], const Ray b[2]) {
    const Key a2 = key_of(a[1], a[0]);
    const Key b1 = key_of(b[0], a[0]), b2 = key_of(b[1], a[0]);
    if (a2.tied_with_base || b1.tied_with_base || b2.tied_with_base) return false;
    const int c1 = compare(b1, a2), c2 = compare(b2, a2);
    if (c1 == 0 || c2 == 0) return false;
    return (c1 < 0) != (c2 < 0);
}

// How near (m) to the joint of neighbours p -> q a meeting of the two is that joint: the joint
// is known within kEps, so along directions theta apart it is known within kEps / sin(theta).
// Tangent neighbours (theta 0 or pi) meet nowhere else, unless along each other.
double joint_reach(const Piece& p, const Piece& q) {
    const double s = std::abs(cross(tangent_at(p, p.g.to), tangent_at(q, q.g.from)));
    return s > 0.0 ? std::max(kEps, kEps / s) : std::numeric_limits<double>::infinity();
}

// The branches of piece p at x: the joint before it (x at its start), the joint after it (at its
// end), or p itself. `start` and `end` are where its ends count as being (a neighbour's joint is
// taken at one point) and reach_start / reach_end how near counts.
int branches_at(const Piece& p, int index, Vec2 x, Vec2 start, double reach_start, Vec2 end, double reach_end,
                Branch out[2]) {
    int n = 0;
    if (glm::length(x - start) <= reach_start) out[n++] = {p.prev, true};
    if (glm::length(x - end) <= reach_end && (n == 0 || out[0].piece != index)) out[n++] = {index, true};
    if (n == 0) out[n++] = {index, false};
    return n;
}

// Whether pieces i and j cross; the point if so.
bool pieces_cross(const std::vector<Piece>& pieces, int i, int j, Vec2& at) {
    const Piece& a = pieces[static_cast<std::size_t>(i)];
    const Piece& b = pieces[static_cast<std::size_t>(j)];
    Vec2 xs[2];
    const int n = intersections(a, b, xs);
    if (n == 0) return false;
    Vec2 a_start = a.g.from, a_end = a.g.to, b_start = b.g.from, b_end = b.g.to;
    double ra_start = kEps, ra_end = kEps, rb_start = kEps, rb_end = kEps;
    if (a.next == j) {  // a's end is b's start: one joint, at one point
        b_start = a_end;
        ra_end = rb_start = joint_reach(a, b);
    }
    if (b.next == i) {
        a_start = b_end;
        rb_end = ra_start = joint_reach(b, a);
    }
    for (int k = 0; k < n; ++k) {
        Branch ba[2], bb[2];
        const int na = branches_at(a, i, xs[k], a_start, ra_start, a_end, ra_end, ba);
        const int nb = branches_at(b, j, xs[k], b_start, rb_start, b_end, rb_end, bb);
        for (int u = 0; u < na; ++u) {
            for (int v = 0; v < nb; ++v) {
                if (ba[u] == bb[v]) continue;  // one joint, seen from both its pieces
                Ray ra[2], rb[2];
                rays_of(pieces, ba[u], xs[k], ra);
                rays_of(pieces, bb[v], xs[k], rb);
                if (separates(ra, rb)) {
                    at = xs[k];
                    return true;
                }
            }
        }
    }
    return false;
}

}  // namespace

//-------------------------------------------------------------------------------------------------
// [SECTION] Search
//-------------------------------------------------------------------------------------------------

std::optional<ContourCrossing> find_contour_crossing(const std::vector<Contour>& contours, CrossingSearchWork* work) {
    const std::vector<Piece> pieces = closed_pieces(contours);
    CrossingSearchWork ignored;
    CrossingSearchWork& done = work ? *work : ignored;
    done = CrossingSearchWork{static_cast<int>(pieces.size()), 0};
    if (pieces.empty()) return std::nullopt;
    std::vector<Aabb> boxes;
    boxes.reserve(pieces.size());
    for (const Piece& p : pieces) boxes.push_back(piece_box(p).grown(kEps));
    const AabbTree tree(boxes);
    std::vector<int> near;
    // Piece by piece in order, each against the later pieces its box overlaps, nearest index
    // first: the first crossing in (contour, segment) order, whatever the tree's layout.
    for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
        near.clear();
        tree.query(boxes[static_cast<std::size_t>(i)], near);
        std::sort(near.begin(), near.end());
        for (const int j : near) {
            if (j <= i) continue;
            ++done.pairs_tested;
            Vec2 at;
            if (!pieces_cross(pieces, i, j, at)) continue;
            const Piece& a = pieces[static_cast<std::size_t>(i)];
            const Piece& b = pieces[static_cast<std::size_t>(j)];
            return ContourCrossing{a.contour, a.segment, b.contour, b.segment, at};
        }
    }
    return std::nullopt;
}

}  // namespace contactlab
