// test_stimuli.cpp — the seeds' stimulus generators: statistics, determinism, and that the
// scenes they write are valid and touchable.
#include "scene_builders.hpp"

#include "haptics/bezier.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/stimuli.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

using namespace contactlab;
using namespace contactlab::test;

TEST_CASE("bumps follow seed 002: counts, heights, widths, spacings, G1 quadratic Beziers") {
    int small = 0, large = 0;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        BumpsDef d;
        d.seed = seed;
        d.small_bumps = static_cast<int>(seed % 4);
        d.large_bumps = seed % 3 == 0 ? 1 : 0;
        const GeneratedScene g = generate_bumps(d);
        CAPTURE(seed);
        REQUIRE(static_cast<int>(g.bumps.size()) == d.small_bumps + d.large_bumps);
        for (std::size_t i = 0; i < g.bumps.size(); ++i) {
            const BumpPlacement& b = g.bumps[i];
            (b.large ? large : small) += 1;
            CHECK(b.height == (b.large ? 0.018 : 0.003));
            CHECK(b.width >= 0.015);
            CHECK(b.width <= 0.030);
            CHECK(b.start >= 0.01);
            CHECK(b.start + b.width <= d.length - 0.01 + 1e-12);
            if (i > 0) {
                const double gap = b.start - (g.bumps[i - 1].start + g.bumps[i - 1].width);
                CHECK(gap >= 0.015 - 1e-12);
                CHECK(gap <= 0.057 + 1e-12);
            }
        }
        // The base shape spans 20 cm vertically over the traced length (bumps add on top).
        double lo = 1e9, hi = -1e9;
        for (const Vec2& p : g.envelope) {
            const bool on_bump = std::any_of(g.bumps.begin(), g.bumps.end(), [&](const BumpPlacement& b) {
                return p.x >= b.start - 1e-12 && p.x <= b.start + b.width + 1e-12;
            });
            if (on_bump) continue;
            lo = std::min(lo, p.y);
            hi = std::max(hi, p.y);
        }
        CHECK(hi - lo <= 0.20 + 1e-12);
        CHECK(hi - lo >= 0.18);  // samples every 2 mm miss the extremes by a little only
        // Every segment is a valid scene (validation passes) and consecutive tangents agree (G1).
        validate_scene(g.scene);
        const auto& segs = g.scene.contours[0].segments;
        for (std::size_t i = 1; i < segs.size(); ++i)
            CHECK(std::abs(cross(segment_end_tangent(segs[i - 1]), segment_start_tangent(segs[i]))) <= 1e-12);
    }
    CHECK(small > 20);
    CHECK(large > 5);
}

TEST_CASE("bumps: same seed gives the same file and another seed a different one") {
    BumpsDef d;
    d.seed = 99;
    const std::string a = scene_to_json_text(generate_bumps(d).scene);
    const std::string b = scene_to_json_text(generate_bumps(d).scene);
    d.seed = 100;
    const std::string c = scene_to_json_text(generate_bumps(d).scene);
    CHECK(a == b);
    CHECK(a != c);
}

TEST_CASE("bump height on the curve: the Bezier through midpoints keeps most of the envelope's height") {
    // A flat base isolates the bump: the curve's peak above the base lies between 80 % and 100 %
    // of the nominal height (the midpoint construction cuts the envelope's corners).
    BumpsDef d;
    d.base_span = 0.0;
    d.small_bumps = 0;
    d.large_bumps = 1;
    const GeneratedScene g = generate_bumps(d);
    double peak = -1.0;
    for (const Segment& s : g.scene.contours[0].segments) {
        if (!segment_is_curve(s)) continue;
        const Bezier b = segment_bezier(s);
        for (int i = 0; i <= 100; ++i) peak = std::max(peak, bezier_point(b, i / 100.0).y);
    }
    CHECK(peak <= 0.018 + 1e-12);
    CHECK(peak >= 0.8 * 0.018);
}

TEST_CASE("block and arc stimuli have the seeds' dimensions") {
    const Scene block = generate_block(0.08);
    const auto& bs = block.contours[0].segments;
    REQUIRE(bs.size() == 3);
    CHECK(segment_start(bs[0]) == Vec2{-0.18, 0.0});
    CHECK(segment_end(bs[0]) == Vec2{0.0, 0.0});
    CHECK(segment_end(bs[1]) == Vec2{0.0, -0.1});

    for (const double h : {0.01, 0.02, 0.03}) {
        const Scene arc = generate_arc(0.30, h);
        validate_scene(arc);
        const auto& a = std::get<ArcSegment>(arc.contours[0].segments[1]);
        CHECK(std::abs(a.center.y + a.radius - h) <= 1e-12);                       // top at height h
        CHECK(std::abs(2.0 * a.radius * std::sin(0.5 * std::abs(a.end_angle - a.start_angle)) - 0.30) <= 1e-12);
        CHECK(a.end_angle < a.start_angle);  // clockwise: a convex bump
        // Pressing 1 mm onto the top: the proxy sits R above it.
        ProxyRig rig(arc);
        rig.proxy->reset({0.0, h + 0.1}, 0.0);
        const ProxyOutput& o = rig.at({0.0, h + 0.026 - 0.001}, 0.0);
        REQUIRE(o.contact);
        CHECK(std::abs(o.proxy.y - (h + 0.026)) <= 1e-9);
    }
    CHECK_THROWS_AS(generate_arc(0.30, 0.2), std::invalid_argument);
    CHECK_THROWS_AS(generate_block(-1.0), std::invalid_argument);
}
