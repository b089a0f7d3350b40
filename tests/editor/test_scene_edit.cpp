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
