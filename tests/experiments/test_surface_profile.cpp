// test_surface_profile.cpp — the resting height of the simulated hand's pad on a sampled contour
// (engine/experiments/protocol/surface_profile.hpp) against a brute-force scan of every point written here
// without the code under test: bit for bit (the hand paths, and so every simulated trial's rows,
// must not change with the speed-up), over seeded random contours, radii, positions and hints.
#include "engine/experiments/protocol/surface_profile.hpp"

#include "engine/experiments/protocol/stimulus.hpp"
#include "haptics/bezier.hpp"
#include "haptics/scene.hpp"
#include "haptics/stimuli.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

using namespace contactlab;
using namespace contactlab::experiments;

namespace {

// Every point, in the order given: the definition of the resting height.
double brute_resting_height(const std::vector<Vec2>& pts, double x, double r) {
    double best = -1e9;
    for (const Vec2& q : pts) {
        const double dx = q.x - x;
        if (std::abs(dx) <= r) best = std::max(best, q.y + std::sqrt(r * r - dx * dx));
    }
    return best;
}

// A contour like the tasks' (a curved base with bumps and a closed underside) sampled at random
// spacing, in a shuffled order.
std::vector<Vec2> random_contour(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double length = 0.05 + 0.25 * u(rng);  // m
    const double step = 1e-4 + 5e-4 * u(rng);    // m
    const double tilt = (u(rng) - 0.5) * 2.0, bumps = 1 + std::floor(8.0 * u(rng)), height = 0.02 * u(rng);
    std::vector<Vec2> pts;
    for (double x = 0.0; x <= length; x += step * (0.5 + u(rng))) {
        const double y = tilt * x + height * std::sin(bumps * 3.14159 * x / length) * std::sin(31.0 * x);
        pts.push_back({x, y});
        if (u(rng) < 0.3) pts.push_back({x, y - 0.01});  // the underside of a solid
    }
    std::shuffle(pts.begin(), pts.end(), rng);
    return pts;
}

}  // namespace

TEST_CASE("resting height: bit for bit the scan of every point, on 200 seeded random contours") {
    std::mt19937_64 rng(20261127);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    long compared = 0, supported = 0;
    for (int c = 0; c < 200; ++c) {
        const std::vector<Vec2> pts = random_contour(rng);
        const SurfaceProfile profile = profile_of(pts);
        REQUIRE(profile.pts.size() == pts.size());
        const double r = 0.002 + 0.04 * u(rng);  // m: from a thin stylus to a large pad
        std::size_t hint = static_cast<std::size_t>(u(rng) * 1e6);  // any start is valid
        // A hand sliding across (and beyond) the contour in small steps, as the paths do, then
        // jumps to random places, and points exactly r from a sample point (the |dx| <= r edge).
        // The cursor's way too (the hand paths'), from a fresh cursor and from a stale one.
        RestingCursor cursor, stale;
        stale.hint = static_cast<std::size_t>(u(rng) * 2.0 * pts.size());
        stale.lo = static_cast<std::size_t>(u(rng) * 2.0 * pts.size());
        stale.hi = static_cast<std::size_t>(u(rng) * 2.0 * pts.size());
        stale.span_valid = true;
        double x = -0.03;
        for (int i = 0; i < 400; ++i, x += 0.001) {
            const double want = brute_resting_height(pts, x, r), got = resting_height(profile, x, r, hint);
            CAPTURE(c);
            CAPTURE(x);
            REQUIRE(got == want);
            REQUIRE(resting_height(profile, x, r, cursor) == want);
            REQUIRE(resting_height(profile, x, r, stale) == want);
            ++compared, supported += want > -1e9;
        }
        for (int i = 0; i < 50; ++i) {  // back and forth in small steps, as a hand path's three heights go
            const double xq = -0.03 + 0.35 * u(rng);
            for (int j = 0; j < 20; ++j) {
                const double xj = xq + (j - 10) * 5e-5;
                REQUIRE(resting_height(profile, xj, r, cursor) == brute_resting_height(pts, xj, r));
            }
        }
        for (int i = 0; i < 100; ++i) {
            const Vec2 q = pts[static_cast<std::size_t>(u(rng) * pts.size()) % pts.size()];
            const double xs[] = {-0.05 + 0.4 * u(rng), q.x + r, q.x - r, std::nextafter(q.x + r, 1.0)};
            for (double xq : xs) {
                std::size_t random_hint = static_cast<std::size_t>(u(rng) * 2.0 * pts.size());
                REQUIRE(resting_height(profile, xq, r, random_hint) == brute_resting_height(pts, xq, r));
                ++compared;
            }
        }
    }
    // The cases reached both answers: supported points and the -1e9 of none within r.
    CHECK(compared == 200 * (400 + 400));
    CHECK(supported > compared / 4);
    CHECK(supported < 200 * 400);
}

TEST_CASE("resting height: analytic cases, a flat floor and a single peak") {
    std::vector<Vec2> floor;
    for (int i = 0; i <= 1000; ++i) floor.push_back({i * 1e-4, 0.0});  // y = 0 from x = 0 to 0.1 m
    const SurfaceProfile p = profile_of(floor);
    std::size_t hint = 0;
    // On the floor a circle of radius r rests with its centre r above it.
    CHECK(resting_height(p, 0.05, 0.026, hint) == doctest::Approx(0.026).epsilon(1e-15));
    // Past the end by less than r: held by the last point, sqrt(r^2 - dx^2) above it.
    CHECK(resting_height(p, 0.11, 0.026, hint) == doctest::Approx(std::sqrt(0.026 * 0.026 - 0.01 * 0.01)).epsilon(1e-12));
    // Beyond r of every point: nothing holds it.
    CHECK(resting_height(p, 0.2, 0.026, hint) == -1e9);
    // A single point raised 5 mm at x = 0.05 m holds the circle up wherever it is the highest support.
    floor[500].y = 0.005;
    const SurfaceProfile peak = profile_of(floor);
    CHECK(resting_height(peak, 0.05, 0.026, hint) == doctest::Approx(0.031).epsilon(1e-12));
    const double dx = 0.01;  // m: off the peak, the peak still holds it higher than the floor
    CHECK(resting_height(peak, 0.05 + dx, 0.026, hint) == doctest::Approx(0.005 + std::sqrt(0.026 * 0.026 - dx * dx)).epsilon(1e-12));
}

TEST_CASE("resting height: seed 002's stimuli, every resting height of a slide bit for bit the scan of every point") {
    // The scenes the bump-counting task makes (generate_bumps), sampled as its hand paths sample
    // them (a point about every 0.25 mm), with a 20 mm pad sliding in 50 um steps.
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        BumpsDef def;
        def.seed = seed * 7919;
        def.small_bumps = static_cast<int>(seed % 3);
        def.large_bumps = static_cast<int>(seed % 2) + 1;
        def.base_span = seed % 2 ? 0.02 : 0.2;
        const Scene scene = generate_bumps(def).scene;
        std::vector<Vec2> pts;
        for (const Segment& seg : scene.contours.front().segments) {
            const int n = surface_intervals(seg);
            for (int i = 0; i <= n; ++i) {
                const double t = static_cast<double>(i) / n;
                if (std::holds_alternative<LineSegment>(seg)) pts.push_back(segment_start(seg) + (segment_end(seg) - segment_start(seg)) * t);
                else pts.push_back(bezier_point(segment_bezier(seg), t));
            }
        }
        const SurfaceProfile profile = profile_of(pts);
        RestingCursor at, ahead;
        for (double x = 0.01; x < def.length - 0.01; x += 5e-5) {
            REQUIRE(resting_height(profile, x, 0.02, at) == brute_resting_height(pts, x, 0.02));
            REQUIRE(resting_height(profile, x + 0.015, 0.02, ahead) == brute_resting_height(pts, x + 0.015, 0.02));
        }
    }
}

TEST_CASE("surface points: a curve's count of intervals is the one its quadrature length gives") {
    // ceil(segment_length / 0.25 mm), at least 2, as the hand paths' points were always cut, over
    // seeded random quadratics (bent, nearly straight, turning back on themselves) and seed 002's.
    auto want = [](const Segment& s) { return std::max(2, static_cast<int>(std::ceil(segment_length(s) / 2.5e-4))); };
    std::mt19937_64 rng(20261129);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    long fast_cases = 0;
    for (int i = 0; i < 20000; ++i) {
        const double size = std::pow(10.0, -4.0 + 2.5 * (0.5 + 0.5 * u(rng)));  // m: 0.1 mm to 30 mm
        const Vec2 p0{u(rng), u(rng)};
        const Vec2 p2 = p0 + size * Vec2{1.0, 0.3 * u(rng)};
        const Vec2 p1 = 0.5 * (p0 + p2) + size * (i % 4 == 0 ? 1e-4 : 0.5) * Vec2{u(rng), u(rng)};
        const Segment seg = QuadSegment{p0, p1, p2};
        REQUIRE(surface_intervals(seg) == want(seg));
        fast_cases += glm::dot(p1 - p0, p2 - p1) > 0.0;
    }
    CHECK(fast_cases > 15000);
    // A curve whose length is a whole number of steps, to the rounding: the quadrature decides.
    const Segment straight = QuadSegment{{0.0, 0.0}, {0.001, 0.0}, {0.002, 0.0}};
    CHECK(surface_intervals(straight) == want(straight));
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        BumpsDef def;
        def.seed = seed;
        def.small_bumps = 2;
        def.large_bumps = 2;
        const Scene scene = generate_bumps(def).scene;
        for (const Segment& seg : scene.contours.front().segments) REQUIRE(surface_intervals(seg) == want(seg));
    }
}
