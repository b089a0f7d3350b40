// test_surface_profile.cpp — the resting height of the simulated hand's pad on a sampled contour
// (engine/experiments/protocol/surface_profile.hpp) against a brute-force scan of every point written here
// without the code under test: bit for bit (the hand paths, and so every simulated trial's rows,
// must not change with the speed-up), over seeded random contours, radii, positions and hints.
#include "engine/experiments/protocol/surface_profile.hpp"

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
        double x = -0.03;
        for (int i = 0; i < 400; ++i, x += 0.001) {
            const double want = brute_resting_height(pts, x, r), got = resting_height(profile, x, r, hint);
            CAPTURE(c);
            CAPTURE(x);
            REQUIRE(got == want);
            ++compared, supported += want > -1e9;
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
