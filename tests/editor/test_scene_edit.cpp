// test_scene_edit.cpp — handles, chains, deletion and direction flips on scenes.
#include "engine/editor/scene_edit.hpp"
#include "haptics/scene_io.hpp"

#include <doctest/doctest.h>

using namespace contactlab;
using namespace contactlab::editor;

TEST_CASE("lines drawn from a chain end extend the chain, in its direction") {
    Scene s;
    s = add_line(s, {0.0, 0.0}, {0.01, 0.0}, 1e-6);
    s = add_line(s, {0.01, 0.0}, {0.02, -0.01}, 1e-6);  // from the last point: appended
    s = add_line(s, {0.0, 0.0}, {-0.01, 0.0}, 1e-6);    // from the first point: prepended, reversed
    REQUIRE(s.contours.size() == 1);
    REQUIRE(s.contours[0].segments.size() == 3);
    CHECK(segment_start(s.contours[0].segments[0]) == Vec2(-0.01, 0.0));
    CHECK(segment_end(s.contours[0].segments[2]) == Vec2(0.02, -0.01));
    CHECK_NOTHROW(validate_scene(s));
    s = add_line(s, {0.5, 0.5}, {0.6, 0.5}, 1e-6);      // elsewhere: a new contour
    CHECK(s.contours.size() == 2);
}

TEST_CASE("moving a joined point moves both segments and picking finds it") {
    Scene s;
    s = add_line(s, {0.0, 0.0}, {0.01, 0.0}, 1e-6);
    s = add_line(s, {0.01, 0.0}, {0.02, 0.0}, 1e-6);
    const auto h = pick_handle(s, {0.0101, 0.0001}, 0.001);
    REQUIRE(h);
    CHECK(handle_position(s, *h) == Vec2(0.01, 0.0));
    s = move_handle(s, *h, {0.01, 0.005});
    CHECK(segment_end(s.contours[0].segments[0]) == Vec2(0.01, 0.005));
    CHECK(segment_start(s.contours[0].segments[1]) == Vec2(0.01, 0.005));
    CHECK_NOTHROW(validate_scene(s));
    CHECK_FALSE(pick_handle(s, {0.5, 0.5}, 0.001));
}

TEST_CASE("deleting splits chains and opens closed contours") {
    Scene s;
    Contour sq;
    sq.closed = true;
    sq.segments = {LineSegment{{0, 0}, {0, 1}}, LineSegment{{0, 1}, {1, 1}}, LineSegment{{1, 1}, {1, 0}},
                   LineSegment{{1, 0}, {0, 0}}};
    s.contours.push_back(sq);
    Scene open = delete_segment(s, 0, 1);
    REQUIRE(open.contours.size() == 1);
    CHECK_FALSE(open.contours[0].closed);
    CHECK(open.contours[0].segments.size() == 3);
    CHECK(segment_start(open.contours[0].segments[0]) == Vec2(1, 1));
    Scene split = delete_segment(open, 0, 1);
    CHECK(split.contours.size() == 2);
    CHECK(segment_count(split) == 2);
    CHECK(delete_segment(delete_segment(split, 1, 0), 0, 0).contours.empty());
}

TEST_CASE("flipping a contour reverses travel (and so the solid side)") {
    Scene s;
    s = add_line(s, {0.0, 0.0}, {0.01, 0.0}, 1e-6);
    s = add_line(s, {0.01, 0.0}, {0.02, 0.01}, 1e-6);
    const Scene f = reverse_contour(s, 0);
    CHECK(segment_start(f.contours[0].segments[0]) == Vec2(0.02, 0.01));
    CHECK(segment_end(f.contours[0].segments[1]) == Vec2(0.0, 0.0));
    CHECK_NOTHROW(validate_scene(f));
}

TEST_CASE("a chain drawn back to its first point closes") {
    Scene s;
    s = add_line(s, {0.0, 0.0}, {0.0, 0.01}, 1e-6);
    s = add_line(s, {0.0, 0.01}, {0.01, 0.01}, 1e-6);
    CHECK_FALSE(s.contours[0].closed);
    s = add_line(s, {0.01, 0.01}, {0.0, 0.0}, 1e-6);  // clockwise triangle: solid inside
    REQUIRE(s.contours.size() == 1);
    CHECK(s.contours[0].closed);
    CHECK(s.contours[0].segments.size() == 3);
    CHECK_NOTHROW(validate_scene(s));
}

TEST_CASE("the arc through three points: centre, radius and direction") {
    // A quarter... half circle of radius 10 mm about the origin, over the top: clockwise.
    const auto cw = arc_through({-0.01, 0.0}, {0.0, 0.01}, {0.01, 0.0});
    REQUIRE(cw);
    CHECK(cw->center.x == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(cw->center.y == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(cw->radius == doctest::Approx(0.01));
    CHECK(cw->start_angle == doctest::Approx(kPi));
    CHECK(cw->end_angle == doctest::Approx(0.0));  // pi -> 0 through pi/2: clockwise, a convex bump
    // Under instead: counter-clockwise (a bowl).
    const auto ccw = arc_through({-0.01, 0.0}, {0.0, -0.01}, {0.01, 0.0});
    REQUIRE(ccw);
    CHECK(ccw->end_angle - ccw->start_angle == doctest::Approx(kPi));
    CHECK(glm::length(segment_end(Segment{*ccw}) - Vec2(0.01, 0.0)) < 1e-15);
    CHECK_FALSE(arc_through({0, 0}, {1, 1}, {2, 2}));  // collinear
}

TEST_CASE("curves and arcs join chains like lines") {
    Scene s;
    s = add_line(s, {-0.02, 0.0}, {-0.01, 0.0}, 1e-6);
    s = add_segment(s, *arc_through({-0.01, 0.0}, {0.0, 0.01}, {0.01, 0.0}), 1e-6);
    s = add_segment(s, QuadSegment{{0.01, 0.0}, {0.015, -0.005}, {0.02, 0.0}}, 1e-6);
    REQUIRE(s.contours.size() == 1);
    CHECK(s.contours[0].segments.size() == 3);
    CHECK_NOTHROW(validate_scene(s));
    // The arc's end is a handle the next segment snapped to.
    const auto h = pick_handle(s, {0.0100001, 0.0}, 1e-4);
    REQUIRE(h);
    CHECK(glm::length(handle_position(s, *h) - Vec2(0.01, 0.0)) < 1e-12);
}

TEST_CASE("closing an open chain joins its ends with a line, opening keeps every segment") {
    // A U of three 1 cm lines: closing adds the 1 cm top from (0.01, 0.01) back to (0, 0.01).
    Scene s;
    s = add_line(s, {0.0, 0.01}, {0.0, 0.0}, 1e-6);
    s = add_line(s, {0.0, 0.0}, {0.01, 0.0}, 1e-6);
    s = add_line(s, {0.01, 0.0}, {0.01, 0.01}, 1e-6);
    REQUIRE(s.contours.size() == 1);
    REQUIRE_FALSE(s.contours[0].closed);
    Scene closed = toggle_closed(s, 0);
    REQUIRE(closed.contours[0].closed);
    REQUIRE(closed.contours[0].segments.size() == 4);
    CHECK(segment_start(closed.contours[0].segments[3]) == Vec2(0.01, 0.01));
    CHECK(segment_end(closed.contours[0].segments[3]) == Vec2(0.0, 0.01));
    CHECK(segment_length(closed.contours[0].segments[3]) == doctest::Approx(0.01).epsilon(1e-12));
    CHECK_NOTHROW(validate_scene(closed));
    // Opened again: closed = false, the four segments kept, still a valid scene.
    Scene opened = toggle_closed(closed, 0);
    CHECK_FALSE(opened.contours[0].closed);
    CHECK(opened.contours[0].segments.size() == 4);
    CHECK_NOTHROW(validate_scene(opened));
    // A chain whose ends already meet closes without a new segment.
    Scene again = toggle_closed(opened, 0);
    CHECK(again.contours[0].closed);
    CHECK(again.contours[0].segments.size() == 4);
    // Out of range: unchanged.
    CHECK(toggle_closed(s, 5).contours.size() == 1);
}
