// test_force_extremes.cpp — the force laws at 1e-6x and 1e6x their nominal values, alone and
// combined: stiffness Ke, force clamp, eccentricity e = k_normal / k_tangential from 1e-3 to 1e3
// (and beyond), damping, friction, servo periods from 10 us to 10 ms. Each checked against the
// law's own formula (seed 000 eq. 1, seed 004 eq. 2) and the clamp.
#include "extremes_fixture.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace contactlab;
using namespace contactlab::extremes;

namespace {

constexpr double R = kNominalRadius;
constexpr double L = kNominalLength;

// Rests the finger on the floor y = 0 and presses it `depth` (m) in (20 steps from touching).
const ProxyOutput& press(Rig& rig, double depth, double x = 0.0) {
    rig.proxy->reset({x, R + 1e-4}, 0.0);
    for (int k = 1; k < 20; ++k) rig.at({x, R - depth * k / 20.0}, 0.0);
    return rig.at({x, R - depth}, 0.0);
}

}  // namespace

TEST_CASE("stiffness 1e-6x to 1e6x and force clamp 1e-6x to 1e6x: F = min(Ke d, F_max), straight up") {
    for (double ke : {1e-6 * kNominalStiffness, 1.0, kNominalStiffness, 1e6, 1e6 * kNominalStiffness}) {
        for (double max_force : {1e-6 * kNominalMaxForce, kNominalMaxForce, 1e6 * kNominalMaxForce}) {
            for (double depth : {1e-8, 1e-6, 1e-3, 0.02}) {
                CAPTURE(ke);
                CAPTURE(max_force);
                CAPTURE(depth);
                Rig rig(floor_at({0.0, 0.0}), def_with(R, L, ke, max_force));
                const ProxyOutput& out = press(rig, depth);
                check_usable(out, max_force);
                REQUIRE(out.contact);
                CHECK(out.force.y == doctest::Approx(std::min(ke * depth, max_force)).epsilon(1e-9));
                CHECK(std::abs(out.force.x) <= 1e-12 * out.force.y);
            }
        }
    }
}

TEST_CASE("ellipsoid field, eccentricity 1e-6 to 1e6 and total stiffness 1e-6x to 1e6x: |F| = |E p| clamped, along -p") {
    for (double e : {1e-6, 1e-3, 0.1, 1.0, 10.0, 1e3, 1e6}) {
        for (double k : {1e-3, kNominalStiffness, 1e9}) {
            CAPTURE(e);
            CAPTURE(k);
            const double kt = tangential_stiffness_from(k, e);
            const double kn = e * kt;
            REQUIRE(std::isfinite(kt));
            REQUIRE(kt > 0.0);
            // Seed 004 eq. 3 (the printed formula) gives back the total stiffness.
            CHECK(std::sqrt((kt * kt + 2.0 * kn * kn) / 3.0) == doctest::Approx(k).epsilon(1e-12));

            ProxyDef def = def_with(R, L, k, kNominalMaxForce);
            def.law.model = ForceModel::ellipsoid;
            def.law.k_tangential = kt;
            def.law.k_normal = kn;
            def.law.mu_static = def.law.mu_dynamic = 10.0;  // the stiction point holds: p has a tangential part
            Rig rig(floor_at({0.0, 0.0}), def);
            press(rig, 0.001);
            // Drag 0.5 mm sideways while pressed: |p_t| / |p_n| = 0.5, inside the cone mu = 10.
            const ProxyOutput& out = rig.at({0.0005, R - 0.001}, 0.0);
            check_usable(out, kNominalMaxForce);
            REQUIRE(out.contact);
            const Vec2 p = out.finger - out.anchor;  // m, penetration from the stiction point
            const double field = std::hypot(kt * p.x, kn * p.y);  // |E p|, N
            const double expected = std::min(field, kNominalMaxForce);
            CHECK(glm::length(out.force) == doctest::Approx(expected).epsilon(1e-9));
            // Along -p: the cross product vanishes, the dot product is negative.
            CHECK(std::abs(out.force.x * p.y - out.force.y * p.x) <= 1e-9 * glm::length(out.force) * glm::length(p));
            CHECK(glm::dot(out.force, p) < 0.0);
        }
    }
}

TEST_CASE("damping 1e-6 to 1e6 N s/m at periods 10 us to 10 ms: finite, clamped, never pulling the finger in") {
    for (double damping : {0.0, 1e-6, 1.0, 1e3, 1e6}) {
        for (double dt : {1e-5, 1e-4, 1e-3, 1e-2}) {
            CAPTURE(damping);
            CAPTURE(dt);
            ProxyDef def = def_with(R, L);
            def.law.damping = damping;
            Rig rig(floor_at({0.0, 0.0}), def);
            rig.proxy->reset({0.0, R + 0.002}, 0.0);
            // In and out of the floor at 10 Hz, 2 mm amplitude about the surface, for 0.3 s.
            const int ticks = static_cast<int>(0.3 / dt);
            for (int k = 0; k <= ticks; ++k) {
                const double y = R - 0.002 * std::sin(2.0 * kPi * 10.0 * k * dt);
                const ProxyOutput& out = rig.at({0.0, y}, 0.0, dt);
                check_usable(out, kNominalMaxForce);
                // Damping adds B v_n only while it pushes the finger out: F_y >= 0, always.
                CHECK(out.force.y >= 0.0);
            }
        }
    }
}

TEST_CASE("friction coefficients 1e-6 to 1e3: the force stays inside the cone and the clamp") {
    for (double mu : {1e-6, 0.5, 10.0, 1e3}) {
        CAPTURE(mu);
        ProxyDef def = def_with(R, L);
        def.law.mu_static = mu;
        def.law.mu_dynamic = 0.5 * mu;
        Rig rig(floor_at({0.0, 0.0}), def);
        press(rig, 0.001);
        // Slide 5 cm and back, 1 mm deep, in 0.1 mm steps.
        for (int k = 0; k <= 1000; ++k) {
            const double x = 0.05 * std::sin(kPi * k / 1000.0);
            const ProxyOutput& out = rig.at({x, R - 0.001}, 0.0);
            check_usable(out, kNominalMaxForce);
            REQUIRE(out.contact);
            CHECK(out.force.y > 0.0);
            // |F_t| <= mu_s F_n (+ rounding): the friction cone of seed 004 §II.
            CHECK(std::abs(out.force.x) <= mu * out.force.y * (1.0 + 1e-9) + 1e-15);
        }
    }
}

TEST_CASE("every force parameter at an extreme at once, random finger motion over the block: finite and clamped") {
    std::mt19937_64 rng(20261123);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (double ke : {1e-3, 1e7, 1e9}) {
        for (double max_force : {1.5e-6, 1.5e6}) {
            for (double e : {1e-3, 1e3}) {
                for (double dt : {1e-5, 1e-2}) {
                    CAPTURE(ke);
                    CAPTURE(max_force);
                    CAPTURE(e);
                    CAPTURE(dt);
                    ProxyDef def = def_with(1e-4, 0.9 * 2.0 * kPi * 1e-4, ke, max_force);
                    def.law.model = ForceModel::ellipsoid;
                    def.law.k_tangential = tangential_stiffness_from(ke, e);
                    def.law.k_normal = e * def.law.k_tangential;
                    def.law.damping = 1e3;
                    def.law.mu_static = 10.0;
                    def.law.mu_dynamic = 5.0;
                    def.law.contacts = ContactForce::sum;
                    def.contact_rule = ContactRule::least_displacement;
                    const Vec2 origin{1e3, -1e3};
                    Rig rig(block_at(origin), def);
                    Vec2 x = origin + Vec2{-0.05, 0.07};
                    double phi = 1e3;
                    rig.proxy->reset(x, phi);
                    for (int k = 0; k < 3000; ++k) {
                        // A random walk with 5 mm steps and jumps of the angle, staying near the block.
                        x += 0.005 * Vec2{unit(rng), unit(rng)};
                        x = origin + glm::clamp(x - origin, Vec2{-0.1, -0.02}, Vec2{0.1, 0.1});
                        phi += 0.5 * unit(rng);
                        check_usable(rig.at(x, phi, dt), max_force);
                    }
                }
            }
        }
    }
}
