// test_planar_arm.cpp — the simulated arm's kept sines (drivers/sim/planar_arm): turned by each
// substep's increment instead of taken from the library, they must still be those of the joint
// angles, to rounding, over slow and fast motion; and the encoders' endpoint must be exactly the
// forward kinematics of the quantised angles.
#include "drivers/sim/planar_arm.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>

using namespace contactlab;
using drivers::sim::PlanarArm;
using drivers::sim::PlanarArmParams;

namespace {

// The endpoint from sines kept over the substeps against the library's at the same angles. Each
// rotation rounds s and c by a few ulps (1e-16 relative); at most 16 rotations pass between
// refreshes, on links of 0.2 m: 16 x 4 x 1.1e-16 x 0.4 m = 3e-15 m. 1e-14 m leaves margin; a
// wrong term in the rotation (a sign, a dropped series term) is off by the turn itself, ~1e-5 m.
constexpr double kTrigTolerance = 1e-14;  // m

double kept_vs_library(const PlanarArm& arm) {
    return glm::length(arm.endpoint() - arm.endpoint_of(arm.q1(), arm.q2()));
}

}  // namespace

TEST_CASE("planar arm: the sines a substep turns follow the joint angles to rounding, slow and fast") {
    const PlanarArmParams params;
    // h (s) and the hand's force (N): 0.1 ms substeps turn the joints by ~1e-4 rad (the series);
    // 20 ms substeps under a hard push turn them by more than 1e-2 rad (the library again).
    struct Case {
        double h, force;
    };
    for (const Case c : {Case{1e-4, 2.0}, Case{1e-4, 20.0}, Case{2e-2, 20.0}}) {
        PlanarArm arm(params);
        REQUIRE(arm.place_at({0.05, 0.1}));
        double worst = 0.0, turned = 0.0;  // m, rad
        for (int i = 0; i < 4000; ++i) {
            const double t = i * c.h;
            // A force that turns both joints both ways, and the motors pulling against it.
            const Vec2 push{c.force * std::sin(7.0 * t + 0.3), c.force * std::cos(5.0 * t)};
            arm.command_force(-0.5 * push);
            const double q1 = arm.q1();
            arm.step(c.h, push);
            turned = std::max(turned, std::abs(arm.q1() - q1));
            worst = std::max(worst, kept_vs_library(arm));
        }
        CAPTURE(c.h);
        CAPTURE(c.force);
        CAPTURE(turned);
        CHECK(worst <= kTrigTolerance);
        if (c.h > 1e-3) CHECK(turned > 1e-2);  // the case meant to leave the series did
    }
}

TEST_CASE("planar arm: the encoders' endpoint is the forward kinematics of the quantised angles, bit for bit") {
    const PlanarArmParams params;
    PlanarArm arm(params);
    REQUIRE(arm.place_at({-0.03, 0.12}));
    const double count = 2.0 * 3.14159265358979323846 / params.encoder_counts;  // rad
    auto quantised = [&](double q) { return std::floor(q / count) * count; };
    for (int i = 0; i < 2000; ++i) {
        // Slow (the counts mostly stay, and the kept sines serve) then faster (they change).
        const double f = i < 1000 ? 0.05 : 3.0;  // N
        arm.step(1e-4, {f * std::sin(0.01 * i), f * std::cos(0.013 * i)});
        const Vec2 expected = arm.endpoint_of(quantised(arm.q1()), quantised(arm.q2()));
        const Vec2 measured = arm.measured_endpoint();
        REQUIRE(measured.x == expected.x);
        REQUIRE(measured.y == expected.y);
    }
}
