// test_contour_crossing.cpp — closed contours that cross themselves or each other
// (haptics/contour_crossing.hpp): analytic shapes with their crossing points, the touching cases
// the rule accepts, invariance under rigid motions, a seeded property test against a brute-force
// O(n^2) reference written here, and the time at 100,000 segments.
#include "haptics/contour_crossing.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/verify/solid_reference.hpp"

#include "scene_builders.hpp"

#include <doctest/doctest.h>

#include <cstdint>
#include <functional>
#include <random>

using namespace contactlab;
using contactlab::test::arc;
using contactlab::test::line;
using contactlab::test::polyline;
using contactlab::test::scene_of;

namespace {

constexpr double mm = 1e-3;  // m

Vec2 P(double x_mm, double y_mm) { return {x_mm * mm, y_mm * mm}; }

std::optional<ContourCrossing> crossing_of(std::initializer_list<Contour> contours) {
    return find_contour_crossing(std::vector<Contour>(contours));
}

// The bow-tie: (0,0) -> (10,10) -> (10,0) -> (0,10) -> back, its diagonals crossing at (5, 5) mm.
Contour bow_tie() { return polyline({P(0, 0), P(10, 10), P(10, 0), P(0, 10)}, true); }

// Two full circles of radius r about (-r, 0) and (r, 0), tangent at the origin: the left one
// clockwise, the right one counter-clockwise (`same_sense` false) is a figure 8, its lobes wound
// opposite ways; both clockwise it is two discs touching at a point.
Contour two_circles(double r, bool same_sense) {
    Contour c;
    c.closed = true;
    c.segments = {arc({-r, 0.0}, r, 0.0, -kTwoPi),
                  same_sense ? arc({r, 0.0}, r, kPi, -kPi) : arc({r, 0.0}, r, kPi, 3.0 * kPi)};
    return c;
}

// A closed square, clockwise (solid inside), lower-left corner at (x, y), side s (mm).
Contour square(double x, double y, double s) {
    return polyline({P(x, y), P(x, y + s), P(x + s, y + s), P(x + s, y)}, true);
}

// Every segment of the contour moved by the rigid motion: rotation by `angle` (rad) about the
// origin, then translation by `shift` (m).
Segment moved(const Segment& s, double angle, Vec2 shift) {
    const double c = std::cos(angle), n = std::sin(angle);
    auto m = [&](Vec2 p) { return Vec2{c * p.x - n * p.y, n * p.x + c * p.y} + shift; };
    if (const auto* l = std::get_if<LineSegment>(&s)) return LineSegment{m(l->from), m(l->to)};
    if (const auto* q = std::get_if<QuadSegment>(&s)) return QuadSegment{m(q->p0), m(q->p1), m(q->p2)};
    if (const auto* k = std::get_if<CubicSegment>(&s)) return CubicSegment{m(k->p0), m(k->p1), m(k->p2), m(k->p3)};
    const auto& a = std::get<ArcSegment>(s);
    return ArcSegment{m(a.center), a.radius, a.start_angle + angle, a.end_angle + angle};
}

std::vector<Contour> moved(const std::vector<Contour>& cs, double angle, Vec2 shift) {
    std::vector<Contour> out = cs;
    for (Contour& c : out)
        for (Segment& s : c.segments) s = moved(s, angle, shift);
    return out;
}

// For a closed contour whose segments 0 and 1 meet at `joint` and cross again away from it: how
// far from the joint (m) the crossing found lies (the test fails if it is another pair).
double neighbour_crossing_distance(const Contour& c, Vec2 joint) {
    const auto x = find_contour_crossing({c});
    REQUIRE(x);
    CHECK(x->segment_a == 0);
    CHECK(x->segment_b == 1);
    return glm::length(x->point - joint);
}

}  // namespace

//-------------------------------------------------------------------------------------------------
// Analytic cases
//-------------------------------------------------------------------------------------------------

TEST_CASE("crossing: a bow-tie of four lines crosses itself where its diagonals meet, (5, 5) mm") {
    const auto x = crossing_of({bow_tie()});
    REQUIRE(x);
    CHECK(x->contour_a == 0);
    CHECK(x->contour_b == 0);
    CHECK(x->segment_a == 0);
    CHECK(x->segment_b == 2);
    // Two lines at right angles, coordinates of 1e-2 m: the root is exact to a few ulps (1e-17 m).
    CHECK(glm::length(x->point - P(5, 5)) < 1e-15);
    // The same four points in the simple order (a square) do not cross.
    CHECK_FALSE(crossing_of({polyline({P(0, 0), P(0, 10), P(10, 10), P(10, 0)}, true)}));
}

TEST_CASE("crossing: a figure 8 of two tangent circles wound opposite ways crosses at the tangent point") {
    const double r = 0.01;  // m
    const auto x = crossing_of({two_circles(r, false)});
    REQUIRE(x);
    CHECK(x->segment_a == 0);
    CHECK(x->segment_b == 1);
    // The circles' tangent point is the origin; the circle/circle root, snapped to the tangency,
    // lies on the centre line at a = (d^2 + r^2 - r^2) / 2d = r from the left centre: exact.
    CHECK(glm::length(x->point) < 1e-15);
    // Wound the same way, the two lobes are two discs touching at a point: a touch, accepted.
    CHECK_FALSE(crossing_of({two_circles(r, true)}));
}

TEST_CASE("crossing: a bow-tie whose diagonals are arcs crosses on its mirror line") {
    // Diagonals (0,0) -> (10,10) and (10,0) -> (0,10) mm as arcs bulging up, mirror images of each
    // other in x = 5 mm, so they cross on it. Arc 0: the circle through both ends with centre
    // (5 + k, 5 - k) mm on the chord's bisector, k = 10 mm (flat enough to stay off the sides).
    const double k = 10.0;
    const Vec2 c0 = P(5 + k, 5 - k), c2 = P(5 - k, 5 - k);
    const double r = glm::length(c0 - P(0, 0));
    Contour c;
    c.closed = true;
    // Arc 0 from (0,0) to (10,10) clockwise (over the top-left), arc 2 from (10,0) to (0,10)
    // counter-clockwise (over the top-right); lines 1 and 3 close the bow-tie.
    const double a0 = angle_of(P(0, 0) - c0), a1 = angle_of(P(10, 10) - c0);
    const double b0 = angle_of(P(10, 0) - c2), b1 = angle_of(P(0, 10) - c2);
    c.segments = {arc(c0, r, a0, a1 - kTwoPi * (a1 > a0 ? 1 : 0)), line(P(10, 10), P(10, 0)),
                  arc(c2, r, b0, b1 + kTwoPi * (b1 < b0 ? 1 : 0)), line(P(0, 10), P(0, 0))};
    const auto x = crossing_of({c});
    REQUIRE(x);
    CHECK(x->segment_a == 0);
    CHECK(x->segment_b == 2);
    // On x = 5 mm, circle 0 at y = 5 - k + sqrt(r^2 - k^2) (the upper point).
    const Vec2 want{5 * mm, (5 - k) * mm + std::sqrt(r * r - k * mm * k * mm)};
    CHECK(glm::length(x->point - want) < 1e-15);
}

TEST_CASE("crossing: a closed contour of quadratic curves crossing itself, within the chords' tolerance") {
    // The bow-tie with quad diagonals: (0,0) -> (10,10) pulled toward (5 - e, 5 + e), and
    // (10,0) -> (0,10) toward (5 + e, 5 + e), mirror images in x = 5 mm. On the mirror line
    // x(s) = 2 (1 - s) s (5 - e) + 10 s^2 = 5, so 2 e s^2 + (10 - 2 e) s - 5 = 0 (mm), and
    // y(s) = 2 (1 - s) s (5 + e) + 10 s^2.
    const double e = 4.0;
    Contour c;
    c.closed = true;
    c.segments = {QuadSegment{P(0, 0), P(5 - e, 5 + e), P(10, 10)}, line(P(10, 10), P(10, 0)),
                  QuadSegment{P(10, 0), P(5 + e, 5 + e), P(0, 10)}, line(P(0, 10), P(0, 0))};
    const double s = (-(10 - 2 * e) + std::sqrt((10 - 2 * e) * (10 - 2 * e) + 40 * e)) / (4 * e);
    const Vec2 want = P(5, 2 * (1 - s) * s * (5 + e) + 10 * s * s);
    const auto x = crossing_of({c});
    REQUIRE(x);
    CHECK(x->segment_a == 0);
    CHECK(x->segment_b == 2);
    // Chords within t = 1e-7 m of each curve; two curves crossing at angle theta meet their
    // chords' crossing within 2 t / sin(theta) of theirs (theta: from the tangents at s).
    const Vec2 t0{2 * (1 - s) * (5 - e) + 2 * s * (10 - (5 - e)), 2 * (1 - s) * (5 + e) + 2 * s * (10 - (5 + e))};
    const Vec2 t2{-t0.x, t0.y};  // the mirror image
    const double sin_theta = std::abs(cross(glm::normalize(t0), glm::normalize(t2)));
    CHECK(glm::length(x->point - want) < 2.0 * kCrossingCurveTolerance / sin_theta);
}

TEST_CASE("crossing: a cubic with a loop, closed by a line, crosses itself within its one segment") {
    // Symmetric in x = w/2: p0 = (0,0), p1 = (w/2 + d, h), p2 = (w/2 - d, h), p3 = (w, 0). With
    // s = 1/2 + v, x(s) - w/2 = v (3w/4 - 3d/2) + v^3 (w + 6d), so the loop closes at
    // v^2 = 3 (2d - w) / (4 (w + 6d)), at y = 3 h (1/4 - v^2).
    const double w = 20, d = 30, h = 20;  // mm
    const double v2 = 3 * (2 * d - w) / (4 * (w + 6 * d));
    Contour c;
    c.closed = true;
    c.segments = {CubicSegment{P(0, 0), P(w / 2 + d, h), P(w / 2 - d, h), P(w, 0)}, line(P(w, 0), P(0, 0))};
    const auto x = crossing_of({c});
    REQUIRE(x);
    CHECK(x->segment_a == 0);
    CHECK(x->segment_b == 0);
    const Vec2 want = P(w / 2, 3 * h * (0.25 - v2));
    // The two branches at s = 1/2 -+ v are mirror images: tangent (x', y') and (x', -y')
    // reversed; x'(s) and y'(s) from the Bernstein derivative.
    const double s = 0.5 + std::sqrt(v2);
    const double xd = 3 * ((1 - s) * (1 - s) * (w / 2 + d) + 2 * (1 - s) * s * (-2 * d) + s * s * (w / 2 + d));
    const double yd = 3 * ((1 - s) * (1 - s) * h - s * s * h);
    const double sin_theta = std::abs(2 * xd * yd) / (xd * xd + yd * yd);
    CHECK(glm::length(x->point - want) < 2.0 * kCrossingCurveTolerance / sin_theta);
    // The message names the one segment.
    Scene scene = scene_of({c});
    try {
        validate_scene(scene);
        FAIL("a looped cubic in a closed contour was accepted");
    } catch (const SceneError& err) {
        CHECK(std::string(err.what()).find("contours[0]: crosses itself at (10.000, ") != std::string::npos);
        CHECK(std::string(err.what()).find("(within segment 0)") != std::string::npos);
    }
}

TEST_CASE("crossing: two overlapping closed squares are refused, two apart are not") {
    // Squares of 10 mm at (0,0) and (5,3): the second's left side x = 5 crosses the first's top
    // y = 10 at (5, 10) mm, and its bottom y = 3 the first's right side x = 10 at (10, 3).
    const auto x = crossing_of({square(0, 0, 10), square(5, 3, 10)});
    REQUIRE(x);
    CHECK(x->contour_a == 0);
    CHECK(x->contour_b == 1);
    // The first crossing in piece order: the first square's segment 1 (its top, (0,10) -> (10,10))
    // against the second's segment 0 (its left side, (5,3) -> (5,13)).
    CHECK(x->segment_a == 1);
    CHECK(x->segment_b == 0);
    CHECK(glm::length(x->point - P(5, 10)) < 1e-15);
    CHECK_FALSE(crossing_of({square(0, 0, 10), square(12, 0, 10)}));
    // One inside the other without crossing is a solid with a hole or two nested solids: allowed.
    CHECK_FALSE(crossing_of({square(0, 0, 10), square(2, 2, 5)}));
}

TEST_CASE("crossing: touching is not crossing (the documented decision)") {
    SUBCASE("two squares sharing a corner") {
        CHECK_FALSE(crossing_of({square(0, 0, 10), square(10, 10, 10)}));
    }
    SUBCASE("a square's corner on another's side, from outside") {
        // A diamond resting its bottom corner on the square's top side.
        CHECK_FALSE(crossing_of({square(0, 0, 10), polyline({P(5, 10), P(2, 13), P(5, 16), P(8, 13)}, true)}));
    }
    SUBCASE("a corner poking through a side is two crossings") {
        const auto x = crossing_of({square(0, 0, 10), polyline({P(5, 9), P(2, 12), P(5, 15), P(8, 12)}, true)});
        REQUIRE(x);
        // The diamond's first side, (5,9) -> (2,12) on y = 14 - x, meets the top y = 10 at x = 4.
        CHECK(glm::length(x->point - P(4, 10)) < 1e-15);
    }
    SUBCASE("two squares sharing part of a side") {
        CHECK_FALSE(crossing_of({square(0, 0, 10), square(10, 4, 10)}));
    }
    SUBCASE("a contour through one vertex twice, its two lobes on either side: an hourglass") {
        // (0,0) -> (5,5) -> (10,0) -> (10,10) -> (5,5) -> (0,10): the lower and upper triangles
        // meet at their tips; the four directions at (5,5) do not alternate.
        CHECK_FALSE(crossing_of({polyline({P(0, 0), P(5, 5), P(10, 0), P(10, 10), P(5, 5), P(0, 10)}, true)}));
    }
    SUBCASE("a circle inside another, tangent to it") {
        Contour big, small;
        big.closed = small.closed = true;
        big.segments = {arc({0.0, 0.0}, 0.02, 0.0, -kTwoPi)};
        small.segments = {arc({0.01, 0.0}, 0.01, 0.0, -kTwoPi)};
        CHECK_FALSE(crossing_of({big, small}));
    }
    SUBCASE("a line tangent to a circle") {
        Contour disc;
        disc.closed = true;
        disc.segments = {arc({0.0, 0.0}, 0.01, 0.0, -kTwoPi)};
        CHECK_FALSE(crossing_of({disc, polyline({P(-20, 10), P(20, 10), P(20, 30), P(-20, 30)}, true)}));
        // 1 um lower the line cuts the circle: a crossing, at x = +-sqrt(r^2 - y^2).
        const double y = 0.01 - 1e-6;
        const auto x = crossing_of({disc, polyline({{-0.02, y}, {0.02, y}, {0.02, 0.03}, {-0.02, 0.03}}, true)});
        REQUIRE(x);
        CHECK(std::abs(std::abs(x->point.x) - std::sqrt(0.01 * 0.01 - y * y)) < 1e-12);
        CHECK(std::abs(x->point.y - y) < 1e-15);
    }
}

TEST_CASE("crossing: a contour through one vertex twice with alternating directions crosses there") {
    // (0,0) -> (5,5) -> (10,10) -> (10,0) -> (5,5) -> (0,10): two straight strokes through (5,5).
    const auto x = crossing_of({polyline({P(0, 0), P(5, 5), P(10, 10), P(10, 0), P(5, 5), P(0, 10)}, true)});
    REQUIRE(x);
    CHECK(glm::length(x->point - P(5, 5)) < 1e-15);
}

TEST_CASE("crossing: joints are not crossings, and open chains may cross anything") {
    // Neighbours share their joint, the closing one too; a single full circle; a lens of two arcs.
    CHECK_FALSE(crossing_of({square(0, 0, 10)}));
    Contour circle;
    circle.closed = true;
    circle.segments = {arc({0.0, 0.0}, 0.01, 0.0, -kTwoPi)};
    CHECK_FALSE(crossing_of({circle}));
    Contour lens;
    lens.closed = true;
    // Circles of 1 cm about (0, -5) and (0, 5) mm meet at (+-8.66, 0) mm, pi/6 and 5 pi/6 from
    // the lower centre: its cap over the top, then the upper circle's cap back under.
    lens.segments = {arc({0.0, -0.005}, 0.01, 5.0 * kPi / 6.0, kPi / 6.0),
                     arc({0.0, 0.005}, 0.01, -kPi / 6.0, -5.0 * kPi / 6.0)};
    CHECK_FALSE(crossing_of({lens}));
    // A spike: out and back along almost the same line, closed by a far side.
    CHECK_FALSE(crossing_of({polyline({P(0, 0), P(0, 10), P(20, 10.001), P(0, 10.002), P(0, 20), P(-5, 20), P(-5, 0)}, true)}));
    // An open zig-zag that crosses itself, and an open chain crossing a closed square: accepted.
    CHECK_FALSE(crossing_of({polyline({P(0, 0), P(10, 10), P(10, 0), P(0, 10)})}));
    CHECK_FALSE(crossing_of({square(0, 0, 10), polyline({P(-5, 5), P(15, 5)})}));
    // Closing the zig-zag makes it the bow-tie.
    CHECK(crossing_of({polyline({P(0, 0), P(10, 10), P(10, 0), P(0, 10)}, true)}));
}

TEST_CASE("crossing: neighbours that cross again a hair from their joint are a crossing") {
    // The generator case of test_contact_fuzz.cpp (a star's last and first arcs, crossing
    // 1.46 mm from their vertex in a sliver 35 um wide), here as a closed contour of the two.
    const ArcSegment a{{0.009204276446599314, 0.011486865140301254}, 0.01744335414020762, -2.954310963962064,
                       -1.585884242196617};
    const ArcSegment b{{0.007430126325182917, -0.019622561355791077}, 0.013751321839737849, 1.4606953979259536,
                       2.865531697997518};
    Contour c;
    c.closed = true;  // closed by a line from b's end back to a's start
    c.segments = {a, b, line(segment_end(Segment{b}), segment_start(Segment{a}))};
    CHECK(neighbour_crossing_distance(c, segment_end(Segment{a})) == doctest::Approx(1.46e-3).epsilon(0.01));
}

//-------------------------------------------------------------------------------------------------
// Invariance
//-------------------------------------------------------------------------------------------------

TEST_CASE("crossing: translated and rotated shapes get the same verdict, the point moved with them") {
    struct Shape {
        const char* name;
        std::vector<Contour> contours;
        double tolerance = 1e-9;  // m: lines and arcs, rounding of coordinates of a few metres
    };
    Contour quads;
    quads.closed = true;
    quads.segments = {QuadSegment{P(0, 0), P(1, 9), P(10, 10)}, line(P(10, 10), P(10, 0)),
                      QuadSegment{P(10, 0), P(9, 9), P(0, 10)}, line(P(0, 10), P(0, 0))};
    const std::vector<Shape> shapes = {
        {"bow-tie", {bow_tie()}},
        {"figure 8 of circles", {two_circles(0.01, false)}},
        {"touching circles", {two_circles(0.01, true)}},
        {"overlapping squares", {square(0, 0, 10), square(5, 3, 10)}},
        {"corner-sharing squares", {square(0, 0, 10), square(10, 10, 10)}},
        {"hourglass", {polyline({P(0, 0), P(5, 5), P(10, 0), P(10, 10), P(5, 5), P(0, 10)}, true)}},
        // Moved control points may round a chord's fit test the other way: the point then moves
        // within the chords' tolerance, amplified by 1 / sin of the crossing angle (about 1.5).
        {"quad bow-tie", {quads}, 4.0 * kCrossingCurveTolerance},
        {"square", {square(0, 0, 10)}},
    };
    const double angles[] = {0.0, 0.3, kPi / 2, 2.0, -kPi * 0.75};
    const Vec2 shifts[] = {{0.0, 0.0}, {0.123, -0.456}, {-2.0, 3.5}};
    for (const Shape& s : shapes) {
        CAPTURE(s.name);
        const auto base = find_contour_crossing(s.contours);
        for (const double angle : angles) {
            for (const Vec2 shift : shifts) {
                CAPTURE(angle);
                CAPTURE(shift);
                const auto x = find_contour_crossing(moved(s.contours, angle, shift));
                REQUIRE(x.has_value() == base.has_value());
                if (!x) continue;
                CHECK(x->segment_a == base->segment_a);
                CHECK(x->segment_b == base->segment_b);
                const double c = std::cos(angle), n = std::sin(angle);
                const Vec2 want = Vec2{c * base->point.x - n * base->point.y, n * base->point.x + c * base->point.y} + shift;
                CHECK(glm::length(x->point - want) < s.tolerance);
            }
        }
    }
}

//-------------------------------------------------------------------------------------------------
// Property: random closed polygons against a brute-force reference
//-------------------------------------------------------------------------------------------------

namespace {

// The reference, written without contour_crossing.cpp: every pair of non-adjacent edges of the
// closed polygons, crossing when each edge's ends lie strictly on either side of the other's line
// (random points are in general position: no three collinear, no vertex on an edge). The first
// pair in (polygon, edge) order, and its point from the two lines' parametric solution.
struct RefCrossing {
    int poly_a = 0, edge_a = 0, poly_b = 0, edge_b = 0;
    Vec2 point{0.0};
};

double orient(Vec2 a, Vec2 b, Vec2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

std::optional<RefCrossing> brute_force(const std::vector<std::vector<Vec2>>& polys) {
    struct Edge {
        int poly, index;
        Vec2 a, b;
    };
    std::vector<Edge> edges;
    for (int p = 0; p < static_cast<int>(polys.size()); ++p) {
        const int n = static_cast<int>(polys[p].size());
        for (int i = 0; i < n; ++i) edges.push_back({p, i, polys[p][i], polys[p][(i + 1) % n]});
    }
    for (std::size_t i = 0; i < edges.size(); ++i) {
        for (std::size_t j = i + 1; j < edges.size(); ++j) {
            const Edge &e = edges[i], &f = edges[j];
            if (e.poly == f.poly) {
                const int n = static_cast<int>(polys[e.poly].size());
                if ((e.index + 1) % n == f.index || (f.index + 1) % n == e.index) continue;  // neighbours
            }
            const double d1 = orient(e.a, e.b, f.a), d2 = orient(e.a, e.b, f.b);
            const double d3 = orient(f.a, f.b, e.a), d4 = orient(f.a, f.b, e.b);
            if ((d1 > 0) == (d2 > 0) || (d3 > 0) == (d4 > 0)) continue;
            const double t = d3 / (d3 - d4);  // along e, from the signed areas
            return RefCrossing{e.poly, e.index, f.poly, f.index, e.a + t * (e.b - e.a)};
        }
    }
    return std::nullopt;
}

// A random polygon of n vertices in a box of side `size` (m) about `centre`: star-shaped (sorted
// by angle: simple) or, with probability `scramble`, with two vertices swapped (often crossing).
std::vector<Vec2> random_polygon(std::mt19937_64& rng, int n, Vec2 centre, double size, double scramble) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::pair<double, Vec2>> pts;
    for (int i = 0; i < n; ++i) {
        const double angle = kTwoPi * u(rng), radius = size * (0.2 + 0.8 * u(rng));
        pts.push_back({-angle, centre + radius * unit_at(angle)});  // decreasing angle: clockwise
    }
    std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Vec2> out;
    for (const auto& p : pts) out.push_back(p.second);
    if (u(rng) < scramble) std::swap(out[static_cast<std::size_t>(rng() % n)], out[static_cast<std::size_t>(rng() % n)]);
    return out;
}

Contour closed_polygon(const std::vector<Vec2>& v) {
    Contour c;
    c.closed = true;
    for (std::size_t i = 0; i < v.size(); ++i) c.segments.push_back(line(v[i], v[(i + 1) % v.size()]));
    return c;
}

}  // namespace

TEST_CASE("crossing: seeded random closed polygons agree with the brute-force reference") {
    std::mt19937_64 rng(20240611);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int crossing = 0, simple = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        CAPTURE(trial);
        std::vector<std::vector<Vec2>> polys;
        const int count = 1 + static_cast<int>(rng() % 3);
        for (int k = 0; k < count; ++k) {
            const int n = 3 + static_cast<int>(rng() % 12);
            const Vec2 centre{0.08 * (u(rng) - 0.5), 0.08 * (u(rng) - 0.5)};
            polys.push_back(random_polygon(rng, n, centre, 0.01 + 0.04 * u(rng), 0.5));
        }
        std::vector<Contour> contours;
        for (const auto& p : polys) contours.push_back(closed_polygon(p));
        const auto want = brute_force(polys);
        const auto got = find_contour_crossing(contours);
        REQUIRE(got.has_value() == want.has_value());
        if (!got) {
            ++simple;
            continue;
        }
        ++crossing;
        CHECK(got->contour_a == want->poly_a);
        CHECK(got->segment_a == want->edge_a);
        CHECK(got->contour_b == want->poly_b);
        CHECK(got->segment_b == want->edge_b);
        // Both roots of the same two lines, of coordinates below 0.1 m: they agree to rounding,
        // amplified by 1 / sin of the angle between the edges.
        const Vec2 ea = polys[want->poly_a][want->edge_a];
        const Vec2 eb = polys[want->poly_a][(want->edge_a + 1) % polys[want->poly_a].size()];
        const Vec2 fa = polys[want->poly_b][want->edge_b];
        const Vec2 fb = polys[want->poly_b][(want->edge_b + 1) % polys[want->poly_b].size()];
        const double sin_theta = std::abs(cross(glm::normalize(eb - ea), glm::normalize(fb - fa)));
        CHECK(glm::length(got->point - want->point) < 1e-15 / sin_theta);
    }
    MESSAGE(crossing, " crossing, ", simple, " simple");
    CHECK(crossing > 500);
    CHECK(simple > 500);
}

//-------------------------------------------------------------------------------------------------
// Scale
//-------------------------------------------------------------------------------------------------

namespace {
// A closed contour of n line segments: the bench's 0.4 m sinusoid (1 cm amplitude, 4 periods) in
// n - 3 chords, closed by a box 5 cm below.
Contour dense_closed(int n) {
    Contour c = contactlab::test::sinusoid_contour(n - 3, 0.01, 4.0);
    const Vec2 start = segment_start(c.segments.front()), end = segment_end(c.segments.back());
    c.segments.push_back(line(end, {end.x, -0.05}));
    c.segments.push_back(line({end.x, -0.05}, {start.x, -0.05}));
    c.segments.push_back(line({start.x, -0.05}, start));
    c.closed = true;
    return c;
}
}  // namespace

TEST_CASE("crossing: 100,000 segments are checked pair by pair only where boxes overlap, found or not") {
    // The search's cost is its exact pair tests (the tree's queries are O(log n) each): counted
    // here, timed in tests/bench/bench_scene_checks.cpp (a clock in a unit test measures the
    // machine, not the code). All pairs would be 5e9 tests: minutes.
    Contour c = dense_closed(100000);
    REQUIRE(c.segments.size() == 100000);
    // A sinusoid drawn left to right closed below is counter-clockwise: reverse nothing, the rule
    // does not care which way round.
    Scene scene = scene_of({c});
    CHECK_NOTHROW(validate_scene(scene));
    CrossingSearchWork work;
    const auto none = find_contour_crossing(scene.contours, &work);
    CHECK_FALSE(none);
    CHECK(work.pieces == 100000);
    // A chord 4 um wide overlaps, in x, only its two neighbours' boxes (grown by 4 nm); the box's
    // sides lie outside the sinusoid's heights but at its two ends. The tree answers a query with
    // whole leaves (AabbTree::kLeafSize, 4 boxes), so a piece's query returns the leaves holding
    // it and its neighbours: at most 8 later pieces, about 3 on average (measured 3.35 a piece).
    CHECK(work.pairs_tested >= 99999);  // every joint is tested, once
    CHECK(work.pairs_tested <= 8 * 100000);
    // The bottom side raised through the sinusoid: it crosses the chords near x = -0.2 m first.
    const Vec2 start = segment_start(c.segments.front()), end = segment_start(c.segments[99997]);
    scene.contours[0].segments[99997] = line(end, {end.x, -0.005});
    scene.contours[0].segments[99998] = line({end.x, -0.005}, {start.x, -0.005});
    scene.contours[0].segments[99999] = line({start.x, -0.005}, start);
    CrossingSearchWork found_work;
    const auto found = find_contour_crossing(scene.contours, &found_work);
    REQUIRE(found);
    CHECK(found->segment_b == 99998);
    CHECK(std::abs(found->point.y + 0.005) < 1e-15);
    // The crossing is among the first chords (x near -0.2 m), so the search stops early; the
    // raised side's box spans the whole width at -5 mm, one more candidate for the chords it
    // overlaps.
    CHECK(found_work.pairs_tested <= 8 * 100000 + 100000);
    MESSAGE("100,000 segments: ", work.pairs_tested, " pair tests (none), ", found_work.pairs_tested, " (found)");
}

//-------------------------------------------------------------------------------------------------
// Property: random closed contours of lines, arcs and curves against dense chords
//-------------------------------------------------------------------------------------------------

namespace {

// A segment from a to b of a random kind: a line, a minor arc bulging either way, a quad or a
// cubic, `bulge` scaling how far it leaves the chord.
Segment random_edge(std::mt19937_64& rng, Vec2 a, Vec2 b, double bulge) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto uni = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
    const Vec2 d = b - a, nl = perp_left(glm::normalize(d)), m = 0.5 * (a + b);
    const double c = glm::length(d), pick = u(rng);
    if (pick < 0.3) return LineSegment{a, b};
    if (pick < 0.55) {
        double sag = uni(-std::min(bulge, 0.5), std::min(bulge, 0.5)) * c;  // m, a minor arc: |sag| <= c / 2
        if (std::abs(sag) < 0.02 * c) sag = std::copysign(0.02 * c, sag);
        const double r = (0.25 * c * c + sag * sag) / (2.0 * std::abs(sag));
        const Vec2 centre = m + (sag - std::copysign(r, sag)) * nl;
        const double start = angle_of(a - centre), sweep = 2.0 * std::asin(std::min(1.0, 0.5 * c / r));
        return ArcSegment{centre, r, start, sag > 0.0 ? start - sweep : start + sweep};
    }
    if (pick < 0.8) return QuadSegment{a, m + uni(-bulge, bulge) * c * nl + uni(-0.3, 0.3) * d, b};
    return CubicSegment{a, a + d / 3.0 + uni(-bulge, bulge) * c * nl, a + 2.0 * d / 3.0 + uni(-bulge, bulge) * c * nl, b};
}

// A star of 3-10 such edges about `centre`, one time in three with two vertices swapped.
Contour random_curved_star(std::mt19937_64& rng, Vec2 centre) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 3 + static_cast<int>(rng() % 8);
    const double r0 = 0.01 + 0.03 * u(rng), bulge = 0.05 + 0.75 * u(rng);
    std::vector<Vec2> v;
    for (int i = 0; i < n; ++i) v.push_back(centre + r0 * (0.3 + 0.7 * u(rng)) * unit_at(-kTwoPi * (i + 0.6 * u(rng) - 0.3) / n));
    if (u(rng) < 0.3) std::swap(v[static_cast<std::size_t>(rng() % n)], v[static_cast<std::size_t>(rng() % n)]);
    Contour c;
    c.closed = true;
    for (int i = 0; i < n; ++i) c.segments.push_back(random_edge(rng, v[i], v[(i + 1) % n], bulge));
    return c;
}

// The reference: every contour as one dense closed polyline (verify::flatten_segment, which
// evaluates the scene's definitions itself, within `tolerance`), then every pair of
// non-neighbouring chords with the strict orientation test, chords taken in runs of 32 whose
// boxes must overlap first.
bool dense_chords_cross(const std::vector<Contour>& contours, double tolerance) {
    struct Chord {
        Vec2 a, b;
        int contour, index, count;
    };
    std::vector<Chord> chords;
    for (int c = 0; c < static_cast<int>(contours.size()); ++c) {
        std::vector<Vec2> pts{segment_start(contours[c].segments.front())};
        for (const Segment& s : contours[c].segments) verify::flatten_segment(s, tolerance, pts);
        pts.back() = pts.front();
        const int n = static_cast<int>(pts.size()) - 1;
        for (int i = 0; i < n; ++i) chords.push_back({pts[i], pts[i + 1], c, i, n});
    }
    constexpr std::size_t kRun = 32;
    struct Run {
        Aabb box;
        std::size_t first, last;
    };
    std::vector<Run> runs;
    for (std::size_t i = 0; i < chords.size(); i += kRun) {
        Run r{Aabb{}, i, std::min(i + kRun, chords.size())};
        for (std::size_t k = r.first; k < r.last; ++k) {
            r.box.grow(chords[k].a);
            r.box.grow(chords[k].b);
        }
        runs.push_back(r);
    }
    for (std::size_t p = 0; p < runs.size(); ++p) {
        for (std::size_t q = p; q < runs.size(); ++q) {
            if (!runs[p].box.overlaps(runs[q].box)) continue;
            for (std::size_t i = runs[p].first; i < runs[p].last; ++i) {
                for (std::size_t j = std::max(i + 1, runs[q].first); j < runs[q].last; ++j) {
                    const Chord &e = chords[i], &f = chords[j];
                    if (e.contour == f.contour && ((e.index + 1) % e.count == f.index || (f.index + 1) % f.count == e.index))
                        continue;
                    const double d1 = orient(e.a, e.b, f.a), d2 = orient(e.a, e.b, f.b);
                    const double d3 = orient(f.a, f.b, e.a), d4 = orient(f.a, f.b, e.b);
                    if ((d1 > 0) != (d2 > 0) && (d3 > 0) != (d4 > 0)) return true;
                }
            }
        }
    }
    return false;
}

}  // namespace

TEST_CASE("crossing: seeded random contours of lines, arcs and curves agree with dense chords") {
    // The reference's chords are 5 times finer than the code's (2e-10 m against 1e-9 m): only a
    // sliver between 0.4 and 2 nm wide could part them, and 1,000 such contours had none.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-0.03, 0.03);
    int crossing = 0, simple = 0;
    for (int trial = 0; trial < 120; ++trial) {
        CAPTURE(trial);
        std::vector<Contour> contours;
        const int count = 1 + static_cast<int>(rng() % 2);
        for (int k = 0; k < count; ++k) contours.push_back(random_curved_star(rng, {u(rng), u(rng)}));
        const bool want = dense_chords_cross(contours, 2e-10);
        const bool got = find_contour_crossing(contours).has_value();
        CHECK(got == want);
        ++(want ? crossing : simple);
    }
    MESSAGE(crossing, " crossing, ", simple, " simple");
    CHECK(crossing > 20);
    CHECK(simple > 20);
}

// What the property test above found while the curves' chords were 1e-7 m: neighbours leaving
// their vertex almost along each other and crossing again tens of micrometres away, in slivers
// thinner than those chords (each pair as the test drew it, closed by lines).
TEST_CASE("regression: a cubic crosses the line after it 47 um from their vertex, in a 56 nm sliver") {
    Contour c;
    c.closed = true;
    const Vec2 joint{-0.012974917672151748, 0.018822739106167233};
    c.segments = {CubicSegment{{-0.010562156694580089, 0.025589144122010993}, {-0.0081729064355131938, 0.022194937913338098},
                               {-0.015699267110434748, 0.022336434795788392}, joint},
                  line(joint, {-0.01640013936937227, 0.023283802872754427}),
                  line({-0.01640013936937227, 0.023283802872754427}, {-0.010562156694580089, 0.025589144122010993})};
    // Where a sampling of the cubic changes side of the line: 47.3 um from the vertex.
    CHECK(neighbour_crossing_distance(c, joint) == doctest::Approx(4.73e-5).epsilon(0.01));
}

TEST_CASE("regression: a quad and the cubic after it cross a few tens of micrometres from their vertex") {
    Contour c;
    c.closed = true;
    const Vec2 joint{0.012212347488452402, 0.025648650083227236};
    const Vec2 start{-0.0050238345813756104, 0.030116631942733518}, end{0.014689216435592321, 0.016910499488570964};
    c.segments = {QuadSegment{start, {0.0027555315433962055, 0.015126324249493096}, joint},
                  CubicSegment{joint, {0.0083876670107039756, 0.02141778332948396}, {0.014551319394436588, 0.020018155432327676}, end},
                  line(end, {end.x, 0.0}), line({end.x, 0.0}, {start.x, 0.0}), line({start.x, 0.0}, start)};
    CHECK(neighbour_crossing_distance(c, joint) < 1e-4);
}
