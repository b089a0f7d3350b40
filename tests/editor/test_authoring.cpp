// test_authoring.cpp — arc handles (end points and the through-point), the centre-radius arc,
// tangent (G1) continuation, and the same tools driven by a script in the real editor. Geometry is
// asserted numerically: points on circles to 1e-12 m (a few ulps of 1e-2 m coordinates through
// atan2/cos/sin), tangent directions equal to 1e-9 (the G1 bound).
#include "engine/editor/scene_edit.hpp"
#include "haptics/scene_io.hpp"
#include "xvfb_editor.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace contactlab;
using namespace contactlab::editor;

namespace {

constexpr double kOnCircle = 1e-12;  // m
constexpr double kG1 = 1e-9;         // |t1 x t2| for unit tangents, and t1 . t2 > 0

double off_circle(const ArcSegment& a, Vec2 p) { return std::abs(glm::length(p - a.center) - a.radius); }
double cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

// A line into a three-point arc (a bump over x = -10..10 mm) into a line.
Scene line_arc_line() {
    Scene s;
    s = add_line(s, {-0.03, 0.0}, {-0.01, 0.0}, 1e-9);
    s = add_segment(s, *arc_through({-0.01, 0.0}, {0.0, 0.01}, {0.01, 0.0}), 1e-9);
    s = add_line(s, {0.01, 0.0}, {0.03, 0.0}, 1e-9);
    return s;
}

bool same_arc(const ArcSegment& a, const ArcSegment& b) {
    return a.center == b.center && a.radius == b.radius && a.start_angle == b.start_angle && a.end_angle == b.end_angle;
}

void check_g1(const Scene& s) {
    for (const Contour& c : s.contours)
        for (std::size_t k = 0; k + 1 < c.segments.size(); ++k) {
            const Vec2 t1 = segment_end_tangent(c.segments[k]), t2 = segment_start_tangent(c.segments[k + 1]);
            CAPTURE(k);
            CHECK(std::abs(cross2(t1, t2)) < kG1);
            CHECK(glm::dot(t1, t2) > 0.0);
            CHECK(glm::length(segment_end(c.segments[k]) - segment_start(c.segments[k + 1])) < kOnCircle);
        }
}

}  // namespace

TEST_CASE("an arc has three handles: start, halfway point, end") {
    const Scene s = line_arc_line();
    const ArcSegment& a = std::get<ArcSegment>(s.contours[0].segments[1]);
    CHECK(handle_count(s.contours[0].segments[1]) == 3);
    CHECK(glm::length(handle_position(s, {0, 1, 1}) - Vec2(0.0, 0.01)) < kOnCircle);
    CHECK(off_circle(a, handle_position(s, {0, 1, 1})) < kOnCircle);
    CHECK(handle_is_end(s, {0, 1, 2}));
    CHECK_FALSE(handle_is_end(s, {0, 1, 1}));
}

TEST_CASE("dragging an arc's end refits it through the other two handles and drags the joined line") {
    const Scene s = move_handle(line_arc_line(), {0, 1, 0}, {-0.012, 0.002});
    const auto& segs = s.contours[0].segments;
    const ArcSegment& a = std::get<ArcSegment>(segs[1]);
    CHECK(glm::length(segment_start(segs[1]) - Vec2(-0.012, 0.002)) < kOnCircle);
    CHECK(off_circle(a, {0.0, 0.01}) < kOnCircle);   // the old halfway point
    CHECK(off_circle(a, {0.01, 0.0}) < kOnCircle);   // the end, kept
    CHECK(segment_end(segs[0]) == segment_start(segs[1]));  // the line follows exactly
    CHECK(std::get<LineSegment>(segs[2]).from == std::get<LineSegment>(line_arc_line().contours[0].segments[2]).from);
    CHECK_NOTHROW(validate_scene(s));
}

TEST_CASE("dragging an arc's through-point keeps its ends and passes through the new point") {
    const Scene before = line_arc_line();
    const Scene s = move_handle(before, {0, 1, 1}, {0.003, 0.015});
    const ArcSegment& a = std::get<ArcSegment>(s.contours[0].segments[1]);
    CHECK(off_circle(a, {0.003, 0.015}) < kOnCircle);
    CHECK(glm::length(segment_start(s.contours[0].segments[1]) - Vec2(-0.01, 0.0)) < kOnCircle);
    CHECK(glm::length(segment_end(s.contours[0].segments[1]) - Vec2(0.01, 0.0)) < kOnCircle);
    CHECK(a.start_angle > a.end_angle);  // still over the top (clockwise), the solid below
    CHECK(std::get<LineSegment>(s.contours[0].segments[0]).to == std::get<LineSegment>(before.contours[0].segments[0]).to);
    // Onto the chord: no circle passes through three points in a line, the edit is refused.
    const Scene flat = move_handle(before, {0, 1, 1}, {0.0, 0.0});
    CHECK(same_arc(std::get<ArcSegment>(flat.contours[0].segments[1]), std::get<ArcSegment>(before.contours[0].segments[1])));
}

TEST_CASE("centre-radius arc: radius from the start, end on the circle, direction as asked") {
    const auto ccw = arc_center_radius({0.01, 0.0}, {0.0, 0.0}, {0.0, 0.02}, 0);  // the short way
    REQUIRE(ccw);
    CHECK(ccw->radius == doctest::Approx(0.01).epsilon(1e-14));
    CHECK(ccw->end_angle - ccw->start_angle == doctest::Approx(kPi / 2).epsilon(1e-14));
    CHECK(glm::length(segment_end(*ccw) - Vec2(0.0, 0.01)) < kOnCircle);
    const auto cw = arc_center_radius({0.01, 0.0}, {0.0, 0.0}, {0.0, 0.02}, -1);  // the long way
    REQUIRE(cw);
    CHECK(cw->end_angle - cw->start_angle == doctest::Approx(-1.5 * kPi).epsilon(1e-14));
    CHECK_FALSE(arc_center_radius({0.0, 0.0}, {0.0, 0.0}, {0.01, 0.0}, 0));  // zero radius
}

TEST_CASE("tangent continuation: the chain's direction at its ends, and arcs that keep it") {
    Scene s;
    s = add_line(s, {0.0, 0.0}, {0.01, 0.01}, 1e-9);
    const Vec2 d = glm::normalize(Vec2(1.0, 1.0));
    const auto at_end = continuation_tangent(s, {0.01, 0.01}, 1e-9);
    REQUIRE(at_end);
    CHECK(std::abs(cross2(*at_end, d)) < 1e-15);
    CHECK(glm::dot(*at_end, d) > 0.0);
    const auto at_start = continuation_tangent(s, {0.0, 0.0}, 1e-9);
    REQUIRE(at_start);
    CHECK(glm::dot(*at_start, d) == doctest::Approx(-1.0));  // leaves backwards: prepended, reversed
    CHECK_FALSE(continuation_tangent(s, {0.005, 0.005}, 1e-9));  // mid-segment: no chain end

    const auto arc = tangent_arc_through({0.0, 0.0}, {1.0, 0.0}, {0.01, 0.01}, {0.02, 0.01});
    REQUIRE(arc);
    CHECK(arc->radius == doctest::Approx(0.01).epsilon(1e-14));
    CHECK(glm::length(arc->center - Vec2(0.0, 0.01)) < kOnCircle);
    CHECK(std::abs(cross2(segment_start_tangent(*arc), Vec2(1.0, 0.0))) < kG1);
    CHECK(segment_start_tangent(*arc).x > 0.0);
    CHECK_FALSE(tangent_arc_through({0.0, 0.0}, {1.0, 0.0}, {0.01, 0.0}, {0.02, 0.01}));  // on the tangent
}

TEST_CASE("authoring in the editor: G1 chain of line, quad, cubic, arcs, undoable, then arc handles dragged") {
    using namespace cli_test;
    TempDir dir;
    const std::string g1 = dir.file("g1.json"), dragged = dir.file("dragged.json"), script = dir.file("g1.txt");
    write_text(script,
               "set snap_mm 1\nset snap_tangent 1\n"
               "tool line\nclick -40 0\nclick -30 0\nrclick -30 0\n"
               "# The quad's control point clicked 3 mm off the tangent: snapped onto it.\n"
               "tool quad\nclick -30 0\nclick -20 3\nclick -10 -10\nrclick -10 -10\n"
               "tool cubic\nclick -10 -10\nclick -4 -17\nclick 4 -10\nclick 10 -10\nrclick 10 -10\n"
               "# Tangent arc: the circle tangent at (10, -10) through (15, -5), up to (10, 0).\n"
               "tool arc\nclick 10 -10\nclick 15 -5\nclick 10 0\nrclick 10 0\n"
               "# Centre-radius: the centre clicked at (12, 4) goes onto the normal, x = 10 mm.\n"
               "tool arc_center\nclick 10 0\nclick 12 4\nclick 2 4\nrclick 6 4\n"
               "expect segments 5\nexpect contours 1\nexpect valid 1\n"
               "undo\nexpect segments 4\nredo\nexpect segments 5\n"
               "save " + g1 + "\nexpect error 0\n"
               "set snap_tangent 0\n"
               "# A bump arc, then its through-point and its start dragged with the select tool.\n"
               "tool line\nclick -30 50\nclick -10 50\nrclick -10 50\n"
               "tool arc\nclick -10 50\nclick 0 60\nclick 10 50\nrclick 10 50\n"
               "tool select\ndrag 0 60 0 65\ndrag -10 50 -12 50\n"
               "expect valid 1\nundo\nundo\nredo\nredo\n"
               "save " + dragged + "\nexpect error 0\nquit\n");
    setenv("TMPDIR", dir.path().c_str(), 1);
    const auto p = editor_test::run_under_xvfb({"edit", "--script", script, "--software", "--validation", "--timeout", "100"});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    CHECK_FALSE(contains(p.err, "FAILED"));

    const Scene s = load_scene_file(g1);
    REQUIRE(s.contours.size() == 1);
    const auto& segs = s.contours[0].segments;
    REQUIRE(segs.size() == 5);
    CHECK(std::holds_alternative<LineSegment>(segs[0]));
    const auto& q = std::get<QuadSegment>(segs[1]);
    CHECK(q.p1.y == 0.0);  // on the line's tangent, not at the clicked 3 mm
    CHECK(q.p1.x == doctest::Approx(-0.020));
    CHECK(std::holds_alternative<CubicSegment>(segs[2]));
    CHECK(std::holds_alternative<ArcSegment>(segs[3]));
    const auto& at = std::get<ArcSegment>(segs[3]);
    CHECK(glm::length(at.center - Vec2(0.010, -0.005)) < kOnCircle);
    CHECK(glm::length(segment_end(at) - Vec2(0.010, 0.0)) < kOnCircle);
    const auto& ac = std::get<ArcSegment>(segs[4]);
    // The centre-radius arc: the centre put on the normal at (10, 0) mm, radius 4 mm, clockwise
    // to where the ray toward (2, 4) mm meets the circle.
    CHECK(glm::length(ac.center - Vec2(0.010, 0.004)) < kOnCircle);
    CHECK(ac.radius == doctest::Approx(0.004).epsilon(1e-12));
    CHECK(glm::length(segment_end(ac) - Vec2(0.006, 0.004)) < kOnCircle);
    check_g1(s);
    CHECK_NOTHROW(validate_scene(s));

    const Scene d = load_scene_file(dragged);
    REQUIRE(d.contours.size() == 2);  // the G1 chain, and the line + arc drawn after it
    REQUIRE(d.contours[1].segments.size() == 2);
    const auto& line = std::get<LineSegment>(d.contours[1].segments[0]);
    const auto& arc = std::get<ArcSegment>(d.contours[1].segments[1]);
    // Through-point dragged to (0, 65) mm, then the start to (-12, 50) mm; the end stays.
    CHECK(glm::length(segment_start(arc) - Vec2(-0.012, 0.050)) < kOnCircle);
    CHECK(off_circle(arc, {0.0, 0.065}) < kOnCircle);
    CHECK(off_circle(arc, {0.010, 0.050}) < kOnCircle);
    CHECK(line.to == segment_start(arc));
}
