// test_force_law.cpp — seed 004's pseudo-ellipsoidal field, its eccentricity/total stiffness, the
// friction cone's stiction point, and normal damping, on the proxy.
#include "scene_builders.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace contactlab;
using namespace contactlab::test;

namespace {
constexpr double R = 0.026;  // m
}

TEST_CASE("ellipsoid field: magnitude |E p| along -p; e = 1 is the spring; extremes stay finite") {
    const Vec2 n{0.0, 1.0};
    for (const Vec2 p : {Vec2{0.001, -0.002}, Vec2{-0.003, -0.0005}, Vec2{0.0, -0.001}, Vec2{0.002, 0.0}}) {
        const double kt = 400.0, kn = 1300.0;
        const Vec2 f = ellipsoid_force(p, n, kt, kn);
        const double expected = std::hypot(kt * p.x, kn * p.y);
        CHECK(std::abs(glm::length(f) - expected) <= 1e-12 * expected);
        CHECK(std::abs(cross(f, p)) <= 1e-15);  // parallel to p ...
        CHECK(glm::dot(f, p) < 0.0);            // ... and pointing back at the anchor
        const Vec2 spring = ellipsoid_force(p, n, 1000.0, 1000.0);
        CHECK(glm::length(spring - (-1000.0 * p)) <= 1e-12);
        for (const double e : {1e-3, 1e3}) {
            const Vec2 g = ellipsoid_force(p, n, 1000.0, 1000.0 * e);
            CHECK(is_finite(g));
        }
    }
    CHECK(ellipsoid_force(Vec2{0.0}, n, 1000.0, 10.0) == Vec2{0.0});
    // Seed 004 eq. 3 and the alternative the diagonal of E suggests.
    const double k = 1000.0, e = 0.4;
    const double k1 = tangential_stiffness_from(k, e), k2 = e * k1;
    CHECK(std::abs(std::sqrt((k1 * k1 + 2.0 * k2 * k2) / 3.0) - k) <= 1e-9);
    const double d1 = tangential_stiffness_from(k, e, TotalStiffness::diagonal_rms), d2 = e * d1;
    CHECK(std::abs(std::sqrt((2.0 * d1 * d1 + d2 * d2) / 3.0) - k) <= 1e-9);
    CHECK(tangential_stiffness_from(k, 1.0) == doctest::Approx(k).epsilon(1e-15));
}

TEST_CASE("ellipsoid on the proxy: pressing straight in feels k_normal, sideways after a stiction hold feels both") {
    Scene s = scene_of({polyline({{-0.3, 0.0}, {0.3, 0.0}})});
    s.force.law.model = ForceModel::ellipsoid;
    s.force.law.k_tangential = 400.0;
    s.force.law.k_normal = 1000.0;
    s.force.law.mu_static = 1.0;
    s.force.law.mu_dynamic = 0.8;
    s.force.max_force = 100.0;
    ProxyRig rig(s);
    rig.proxy->reset({0.0, 0.1}, 0.0);
    const ProxyOutput& a = rig.at({0.0, R - 0.001}, 0.0);
    REQUIRE(a.contact);
    CHECK(std::abs(a.force.y - 1000.0 * 0.001) <= 1e-9);  // k_normal * depth
    CHECK(std::abs(a.force.x) <= 1e-12);
    // Move 0.5 mm sideways (inside the cone: 0.5 mm <= mu_s * 1 mm): the stiction point holds.
    const ProxyOutput& b = rig.at({0.0005, R - 0.001}, 0.0);
    CHECK_FALSE(b.sliding);
    CHECK(std::abs(b.anchor.x - 0.0) <= 1e-12);
    const double expected = std::hypot(400.0 * 0.0005, 1000.0 * 0.001);
    CHECK(std::abs(glm::length(b.force) - expected) <= 1e-9);
    CHECK(b.force.x < 0.0);  // pulled back toward the stiction point
}

TEST_CASE("friction cone: the stiction point holds inside the cone and slides along its edge outside") {
    Scene s = scene_of({polyline({{-0.3, 0.0}, {0.3, 0.0}})});
    s.force.law.mu_static = 0.5;
    s.force.law.mu_dynamic = 0.3;
    s.force.max_force = 100.0;
    ProxyRig rig(s);
    const double depth = 0.002, k = 1000.0;
    rig.proxy->reset({0.0, 0.1}, 0.0);
    rig.at({0.0, R - depth}, 0.0);
    int held = 0, slid = 0;
    for (double x = 0.0; x <= 0.01; x += 1e-5) {
        const ProxyOutput& o = rig.at({x, R - depth}, 0.0);
        REQUIRE(o.contact);
        const double ft = -o.force.x, fn = o.force.y;  // friction opposes the motion (+x)
        CHECK(std::abs(fn - k * depth) <= 1e-9);
        if (x <= 0.5 * depth - 1e-9) {
            // Inside the cone (|x| <= mu_s * depth): held at x = 0, tangential force k x.
            CHECK_FALSE(o.sliding);
            CHECK(std::abs(o.anchor.x) <= 1e-12);
            CHECK(std::abs(ft - k * x) <= 1e-9);
            ++held;
        } else if (o.sliding) {
            // Sliding: the stiction point trails the finger so that |F_t| = mu_d F_n.
            CHECK(std::abs(ft / fn - 0.3) <= 1e-9);
            CHECK(std::abs(o.anchor.y - R) <= 1e-12);  // on the surface (the proxy's height)
            ++slid;
        } else {
            // Re-stuck after a slip: inside the cone again, above the dynamic edge.
            CHECK(ft / fn <= 0.5 + 1e-9);
            CHECK(ft / fn >= 0.3 - 1e-9);
        }
    }
    CHECK(held == 100);
    // With mu_d < mu_s the point sticks again after each slip (stick-slip): it slips once the
    // finger has moved (mu_s - mu_d) depth = 0.4 mm past it, i.e. every 40 ticks over 9 mm.
    CHECK(slid >= 20);
    CHECK(slid <= 25);
}

TEST_CASE("normal damping adds B times the penetration speed and never pulls the finger in") {
    Scene s = scene_of({polyline({{-0.3, 0.0}, {0.3, 0.0}})});
    s.force.law.damping = 2.0;  // N s/m
    s.force.max_force = 100.0;
    ProxyRig rig(s);
    rig.proxy->reset({0.0, 0.1}, 0.0);
    const double dt = 1e-3, v = 0.05;  // s, m/s pressing in
    rig.proxy->update({0.0, R - 0.001}, 0.0, dt);
    const ProxyOutput& in = rig.proxy->update({0.0, R - 0.001 - v * dt}, 0.0, dt);
    CHECK(std::abs(in.force.y - (1000.0 * (0.001 + v * dt) + 2.0 * v)) <= 1e-9);
    // Pulling out fast: damping would exceed the spring; the normal force floors at zero.
    const ProxyOutput& out = rig.proxy->update({0.0, R - 0.0001}, 0.0, dt);
    CHECK(out.force.y >= 0.0);
    CHECK(std::abs(out.force.y) <= 1e-12);
}
