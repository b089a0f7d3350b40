// test_draw_list.cpp — the CPU half of the drawing path: geometry counts, anti-aliasing fringes,
// flattening within the pixel tolerance, command merging, stencil fills. No GPU needed.
#include "engine/render/draw_list.hpp"
#include "engine/render/frame.hpp"
#include "engine/render/frame_parts.hpp"
#include "engine/render/view.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

using namespace contactlab;
using namespace contactlab::render;

TEST_CASE("draw list: a polyline stroke is 4 vertices per point, 3 strips per segment, faded edges") {
    DrawList list(100, 100);
    const P2 pts[3] = {{10, 10}, {50, 10}, {50, 60}};
    list.stroke(pts, false, 3.0f, Color{200, 100, 50, 255});
    CHECK(list.vertices().size() == 12);
    CHECK(list.indices().size() == 2 * 18);
    REQUIRE(list.commands().size() == 1);
    CHECK(list.commands()[0].kind == DrawKind::triangles);
    // Outer vertices transparent (the fringe), inner ones opaque, 1 px apart: core half-width 1,
    // offset along the left normal (0, 1) of the first segment.
    CHECK(list.vertices()[0].color.a == 0);
    CHECK(list.vertices()[1].color.a == 255);
    CHECK(std::abs(list.vertices()[0].y - 12.0f) < 1e-5f);
    CHECK(std::abs(list.vertices()[1].y - 11.0f) < 1e-5f);
    CHECK(std::abs(list.vertices()[2].y - 9.0f) < 1e-5f);
    // Miter at the corner keeps the width along both segments: offset (-1, 1) * core.
    CHECK(std::abs(list.vertices()[5].x - 49.0f) < 1e-4f);
    CHECK(std::abs(list.vertices()[5].y - 11.0f) < 1e-4f);
}

TEST_CASE("draw list: sub-pixel strokes fade instead of thinning, duplicate points are merged") {
    DrawList list(100, 100);
    const P2 pts[4] = {{10, 10}, {10, 10}, {20, 10}, {20.0001f, 10}};
    list.stroke(pts, false, 0.5f, Color{255, 255, 255, 200});
    CHECK(list.vertices().size() == 8);  // two points survive
    CHECK(list.vertices()[1].color.a == 100);
}

TEST_CASE("draw list: consecutive plain draws merge into one command, stencil fills add mark + cover") {
    DrawList list(64, 64);
    list.line({0, 0}, {10, 10}, 1.0f, Color{});
    list.fill_disc({30, 30}, 5.0f, Color{});
    CHECK(list.commands().size() == 1);
    const P2 poly[5] = {{0, 0}, {40, 0}, {20, 20}, {40, 40}, {0, 40}};  // concave
    list.fill_polygon(poly, Color{});
    list.line({0, 0}, {10, 10}, 1.0f, Color{});
    REQUIRE(list.commands().size() == 4);
    CHECK(list.commands()[1].kind == DrawKind::stencil_mark);
    CHECK(list.commands()[1].index_count == 3 * 3);  // a fan of n - 2 triangles
    CHECK(list.commands()[2].kind == DrawKind::stencil_cover);
    CHECK(list.commands()[2].index_count == 6);
    CHECK(list.commands()[3].kind == DrawKind::triangles);
    for (uint32_t i : list.indices()) CHECK(i < list.vertices().size());
}

TEST_CASE("draw list: arcs are flattened within the pixel tolerance, and no finer than needed") {
    for (double r : {0.5, 3.0, 40.0, 700.0, 20000.0})
        for (double sweep : {0.1, 1.0, std::numbers::pi, 2.0 * std::numbers::pi})
            for (double tol : {0.1, 0.2, 0.5}) {
                if (r <= tol) continue;  // circles smaller than the tolerance are not refined
                const int n = arc_chord_count(r, sweep, tol);
                const double sagitta = r * (1.0 - std::cos(0.5 * sweep / n));
                CHECK(sagitta <= tol * (1.0 + 1e-9));
                if (n > 1) CHECK(r * (1.0 - std::cos(0.5 * sweep / (n - 1))) > tol);  // n - 1 would not do
            }
    std::vector<P2> pts;
    arc_points({0, 0}, 100.0, 0.0, std::numbers::pi, 0.2, pts);
    CHECK(pts.size() == static_cast<size_t>(arc_chord_count(100.0, std::numbers::pi, 0.2) + 1));
    CHECK(std::abs(pts.front().x - 100.0f) < 1e-4f);
    CHECK(std::abs(pts.back().x + 100.0f) < 1e-4f);
}

TEST_CASE("view: world y up maps to pixel y down, fit keeps the box inside with equal scales") {
    Aabb box;
    box.grow(Vec2(-0.2, -0.05));
    box.grow(Vec2(0.2, 0.05));
    const View v = fit_view(box, 400, 200, 0.0);
    CHECK(v.px_per_m == doctest::Approx(1000.0));
    const P2 top_left = v.to_px({-0.2, 0.1});
    CHECK(top_left.x == doctest::Approx(0.0));
    CHECK(top_left.y == doctest::Approx(0.0));
    CHECK(v.to_px({0.0, -0.1}).y == doctest::Approx(200.0));
    const Vec2 back = v.to_world(123.0, 45.0);
    CHECK(v.to_px(back).x == doctest::Approx(123.0));
    CHECK(v.to_px(back).y == doctest::Approx(45.0));
}

TEST_CASE("flattening a scene arc: endpoints exact, every point on the circle") {
    View v;
    v.width = 640;
    v.height = 360;
    v.center = {0.0, 0.0};
    v.px_per_m = 3000.0;
    const ArcSegment arc{{0.01, -0.02}, 0.05, std::numbers::pi, 2.0 * std::numbers::pi};
    std::vector<P2> pts;
    parts::flatten_segment(arc, v, false, pts);
    REQUIRE(pts.size() >= 3);
    const P2 c = v.to_px(arc.center);
    for (const P2& p : pts) CHECK(glm::length(p - c) == doctest::Approx(0.05 * 3000.0).epsilon(1e-5));
    CHECK(glm::length(pts.front() - v.to_px({-0.04, -0.02})) < 1e-3f);
    CHECK(glm::length(pts.back() - v.to_px({0.06, -0.02})) < 1e-3f);
}

namespace {
// Distance (px) from p to segment ab.
float distance_to(P2 p, P2 a, P2 b) {
    const P2 ab = b - a;
    const float t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
    return glm::length(p - (a + t * ab));
}
}  // namespace

TEST_CASE("simplify_polyline: dense chains shrink, every dropped point stays within the tolerance") {
    std::vector<P2> straight;
    for (int i = 0; i <= 1000; ++i) straight.push_back({i * 0.01f, 5.0f + i * 0.003f});
    simplify_polyline(straight, 0.05f);
    CHECK(straight.size() == 2);

    std::vector<P2> wave, original;
    for (int i = 0; i <= 20000; ++i) {
        const float x = i * 0.02f;  // 50 points per pixel
        wave.push_back({x, 50.0f + 20.0f * std::sin(x * 0.05f) + 0.01f * std::sin(x * 40.0f)});
    }
    original = wave;
    simplify_polyline(wave, 0.05f);
    CHECK(wave.size() < original.size() / 20);
    CHECK(wave.front() == original.front());
    CHECK(wave.back() == original.back());
    for (const P2& p : original) {
        float best = 1e9f;
        for (size_t k = 0; k + 1 < wave.size(); ++k) best = std::min(best, distance_to(p, wave[k], wave[k + 1]));
        CHECK(best <= 0.05f + 1e-4f);
    }
}

namespace {
// Quadratic Bezier segments, when the scene model has them (alternative 2 of Segment): flattened
// within the pixel tolerance.
template <size_t I>
void check_quad_flattening() {
    if constexpr (I < std::variant_size_v<Segment>) {
        using Quad = std::variant_alternative_t<I, Segment>;
        if constexpr (requires(Quad q) { q.p2; }) {
            Quad q{};
            q.p0 = {0.0, 0.0};
            q.p1 = {0.05, 0.1};
            q.p2 = {0.1, 0.0};
            View v;
            v.width = 640;
            v.height = 360;
            v.center = {0.05, 0.03};
            v.px_per_m = 3000.0;
            std::vector<P2> pts;
            parts::flatten_segment(Segment{q}, v, false, pts);
            REQUIRE(pts.size() >= 3);
            CHECK(glm::length(pts.front() - v.to_px(q.p0)) < 1e-3f);
            CHECK(glm::length(pts.back() - v.to_px(q.p2)) < 1e-3f);
            std::vector<P2> dense;
            for (int k = 0; k <= 20000; ++k) {
                const double t = k / 20000.0;
                dense.push_back(v.to_px((1 - t) * (1 - t) * q.p0 + 2 * (1 - t) * t * q.p1 + t * t * q.p2));
            }
            for (size_t i = 0; i + 1 < pts.size(); ++i) {
                const P2 mid = 0.5f * (pts[i] + pts[i + 1]);
                float best = 1e9f;
                for (const P2& d : dense) best = std::min(best, glm::length(d - mid));
                CHECK(best <= kFlattenTolerancePx + 0.02);
            }
        }
    }
}
}  // namespace

TEST_CASE("flattening a quadratic Bezier (if the scene model has curves): within the pixel tolerance") {
    check_quad_flattening<2>();
}
