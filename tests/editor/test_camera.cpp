// test_camera.cpp — pan, cursor-anchored zoom and fit.
#include "engine/editor/camera.hpp"
#include "engine/editor/rulers.hpp"

#include <doctest/doctest.h>

using namespace contactlab;
using namespace contactlab::editor;

TEST_CASE("zoom keeps the world point under the cursor fixed") {
    Camera cam;
    cam.resize(1280, 720);
    const Vec2 before = cam.view().to_world(900.0, 200.0);
    cam.zoom_at(900.0, 200.0, 1.15);
    const Vec2 after = cam.view().to_world(900.0, 200.0);
    CHECK(after.x == doctest::Approx(before.x).epsilon(1e-12));
    CHECK(after.y == doctest::Approx(before.y).epsilon(1e-12));
    CHECK(cam.view().px_per_m == doctest::Approx(2000.0 * 1.15));
    // Far out and far in stop at the limits.
    for (int i = 0; i < 200; ++i) cam.zoom_at(10.0, 10.0, 0.5);
    CHECK(cam.view().px_per_m == Camera::kMinZoom);
    for (int i = 0; i < 200; ++i) cam.zoom_at(10.0, 10.0, 2.0);
    CHECK(cam.view().px_per_m == Camera::kMaxZoom);
}

TEST_CASE("pan moves the world with the cursor") {
    Camera cam;
    cam.resize(800, 600);
    const Vec2 grabbed = cam.view().to_world(100.0, 100.0);
    cam.pan(50.0, -30.0);
    const Vec2 now = cam.view().to_world(150.0, 70.0);
    CHECK(now.x == doctest::Approx(grabbed.x));
    CHECK(now.y == doctest::Approx(grabbed.y));
}

TEST_CASE("fit shows the whole box, centred") {
    Camera cam;
    cam.resize(1000, 500);
    Aabb box;
    box.grow(Vec2(-0.1, 0.0));
    box.grow(Vec2(0.1, 0.05));
    cam.fit(box);
    const Aabb shown = cam.view().world_bounds();
    CHECK(shown.lo.x <= -0.1);
    CHECK(shown.hi.x >= 0.1);
    CHECK(shown.lo.y <= 0.0);
    CHECK(shown.hi.y >= 0.05);
    CHECK(cam.view().center.x == doctest::Approx(0.0));
    CHECK(cam.view().center.y == doctest::Approx(0.025));
}

TEST_CASE("ruler labels step by 1, 2 or 5 x 10^k mm, at least the asked spacing apart") {
    CHECK(ruler_step(2000.0, 90.0) == doctest::Approx(0.05));    // 2 px/mm: 50 mm = 100 px
    CHECK(ruler_step(20000.0, 90.0) == doctest::Approx(0.005));  // 20 px/mm: 5 mm = 100 px
    CHECK(ruler_step(1.0e6, 90.0) == doctest::Approx(0.0001));   // 1000 px/mm: 0.1 mm = 100 px
    CHECK(ruler_step(900.0, 90.0) == doctest::Approx(0.1));      // exactly 90 px
}
