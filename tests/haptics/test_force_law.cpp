// test_force_law.cpp — seed 004's pseudo-ellipsoidal field, its eccentricity/total stiffness, the
// friction cone's stiction point, and normal damping, on the proxy.
#include "scene_builders.hpp"
#include "haptics/scene_io.hpp"

#include <doctest/doctest.h>

#include <cmath>

using namespace contactlab;
using namespace contactlab::test;

namespace {
constexpr double R = 0.026;  // m
}

TEST_CASE("ellipsoid field: magnitude |E p| along -p, e = 1 is the spring, extremes stay finite") {
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

// Seed 002 §2.3's multi-contact force: a valley whose sides (at +-a to the horizontal, solid
// below) are separate surfaces, joined through a 1 cm deep slot the pad cannot reach, and
// narrower than the pad. Each side's c-space
// piece is its offset line, so the finger's depth behind side i is d_i = (x_c - x_f) . n_i with x_c
// the point R from both sides, and the summed force is Ke times the sum of d_i n_i over the sides
// the finger is behind (d_i > 0). Pressing straight down by h gives 2 Ke h cos^2 a, against Ke h
// for the god-object's one spring.
TEST_CASE("sum over contact pairs: a valley pushes with each side the finger is behind, continuously") {
    const double a = 0.2;  // rad, within the pad's half-angle L / 2R = 0.385 so both contacts are on the pad
    // h small enough that the slot's top corners stay beyond the pad's circle (R from x_f).
    const double Ke = 1000.0, h = 0.0003, w = 0.0005;  // N/m, m, m (slot half-width)
    const double t = std::tan(a);
    Scene s = scene_of({polyline({{-w - 0.1, 0.1 * t}, {-w, 0.0}, {-w, -0.01}, {w, -0.01}, {w, 0.0}, {w + 0.1, 0.1 * t}})});
    s.force.stiffness = Ke;
    s.force.max_force = 100.0;
    const Vec2 corner{0.0, R / std::cos(a) - w * t};  // the proxy in the valley: R from both sides
    const Vec2 n1{std::sin(a), std::cos(a)}, n2{-std::sin(a), std::cos(a)};  // free-side normals
    auto depth = [&](Vec2 f, Vec2 n) { return glm::dot(corner - f, n); };
    auto summed_force = [&](Vec2 f) {
        Vec2 F{0.0};
        for (const Vec2 n : {n1, n2}) F += Ke * std::max(0.0, depth(f, n)) * n;
        return F;
    };

    Scene summed = s;
    summed.force.law.contacts = ContactForce::sum;
    ProxyRig one(s), sum(summed);
    for (ProxyRig* rig : {&one, &sum}) rig->proxy->reset(corner + Vec2{0.0, 0.05}, 0.0);
    // Straight down, then 0.05 mm to the side (still inside the corner's normal cone, |x/h| < tan a).
    for (const Vec2 f : {corner - Vec2{0.0, h}, corner + Vec2{0.00005, -h}}) {
        const ProxyOutput& p = one.at(f, 0.0);
        const ProxyOutput& q = sum.at(f, 0.0);
        REQUIRE(p.contact_count == 2);
        REQUIRE(q.contact_count == 2);
        CHECK(glm::length(p.proxy - corner) <= 1e-12);
        CHECK(glm::length(p.force - Ke * (corner - f)) <= 1e-9);
        CHECK(glm::length(q.force - summed_force(f)) <= 1e-9);
        CHECK(q.proxy == p.proxy);  // the rule changes the force, not the proxy or l_d
        CHECK(q.l_d == p.l_d);
    }
    CHECK(std::abs(sum.at(corner - Vec2{0.0, h}, 0.0).force.y - 2.0 * Ke * h * std::cos(a) * std::cos(a)) <= 1e-9);

    // Slide h deep (vertically) across the valley. The finger crosses the far side's offset line
    // before the proxy reaches the corner: from there on the far side pushes too. Every tick
    // matches the analytic sum; with one side under the finger it equals the god-object's force;
    // and since each d_i moves by at most |dx| per tick and starts at 0, |dF| <= 2 Ke |dx|.
    sum.proxy->reset(corner + Vec2{-0.03, 0.05}, 0.0);
    one.proxy->reset(corner + Vec2{-0.03, 0.05}, 0.0);
    const double dx = 1e-5;  // m per tick
    Vec2 previous{0.0};
    int both = 0, single = 0;
    for (int k = 0; k <= 6000; ++k) {
        const double x = -0.03 + k * dx;
        const Vec2 f{x, corner.y + std::abs(x) * t - h};
        const ProxyOutput& q = sum.at(f, 0.0);
        const ProxyOutput& p = one.at(f, 0.0);
        REQUIRE(q.contact);
        CHECK(glm::length(q.force - summed_force(f)) <= 1e-9);
        if (std::min(depth(f, n1), depth(f, n2)) < 0.0) {
            ++single;
            CHECK(glm::length(q.force - p.force) <= 1e-9);
        } else {
            ++both;
        }
        if (k > 0) CHECK(glm::length(q.force - previous) <= 2.0 * Ke * dx * (1.0 + 1e-9) + 1e-12);
        previous = q.force;
    }
    CHECK(single > 5000);
    CHECK(both > 100);  // |x| < h / (2 tan a) = 0.74 mm: 148 ticks

    // Seed 002 traces a pair across adjacent segments: in a V whose sides meet at one vertex the
    // sides are one pair, so the sum is the god-object's single spring.
    Scene v = scene_of({polyline({{-0.1, 0.1 * t}, {0.0, 0.0}, {0.1, 0.1 * t}})});
    v.force = summed.force;
    ProxyRig vee(v);
    const Vec2 v_corner{0.0, R / std::cos(a)};
    vee.proxy->reset(v_corner + Vec2{0.0, 0.05}, 0.0);
    const ProxyOutput& o = vee.at(v_corner - Vec2{0.0, h}, 0.0);
    REQUIRE(o.contact_count == 2);
    CHECK(glm::length(o.force - Vec2{0.0, Ke * h}) <= 1e-9);
}

// The proxy keeps the penalty sum from popping through: pressed 3 mm into a 1 mm wall, the finger
// is behind both faces' pieces, but the proxy is behind the far face's, so only the near face
// pushes, Ke d back toward the side the finger came from.
TEST_CASE("sum over contact pairs: a thin wall's far face never pushes the finger through") {
    const double Ke = 1000.0, d = 0.003;  // N/m, m
    // A 1 mm wall along y, solid between x = 0 and x = 0.001 (closed, clockwise: solid on the right).
    Scene s = scene_of({polyline({{0.0, -0.1}, {0.0, 0.1}, {0.001, 0.1}, {0.001, -0.1}}, true)});
    s.force.stiffness = Ke;
    s.force.max_force = 100.0;
    s.force.law.contacts = ContactForce::sum;
    ProxyRig rig(s);
    rig.proxy->reset({-0.05, 0.0}, kPi / 2);  // pad facing +x
    for (double x = -0.05; x <= -R + d; x += 1e-4) rig.at({x, 0.0}, kPi / 2);
    const ProxyOutput& o = rig.at({-R + d, 0.0}, kPi / 2);
    REQUIRE(o.contact);
    CHECK(std::abs(o.proxy.x - (-R)) <= 1e-12);
    CHECK(std::abs(o.force.x - (-Ke * d)) <= 1e-9);
    CHECK(std::abs(o.force.y) <= 1e-12);
}

TEST_CASE("switching the force model keeps the stiffness felt pressing straight in, and the eccentricity") {
    ForceDef f;
    f.stiffness = 1500.0;  // N/m
    set_force_model(f, ForceModel::ellipsoid);
    CHECK(f.law.model == ForceModel::ellipsoid);
    CHECK(f.law.k_normal == 1500.0);
    CHECK(f.law.k_tangential == 1500.0);  // e = 1: the same wall
    // Pressing straight in (p along the normal) the ellipsoid gives k_normal |p|, as the spring did.
    const Vec2 n{0.0, 1.0};
    const Vec2 p{0.0, -0.001};
    CHECK(glm::length(ellipsoid_force(p, n, f.law.k_tangential, f.law.k_normal)) == doctest::Approx(1.5).epsilon(1e-12));
    // The user adds anisotropy (e = 0.4), goes back to the spring and raises Ke: e is kept.
    f.law.k_tangential = f.law.k_normal / 0.4;
    set_force_model(f, ForceModel::spring);
    CHECK(f.stiffness == 1500.0);
    f.stiffness = 2000.0;
    set_force_model(f, ForceModel::ellipsoid);
    CHECK(f.law.k_normal == 2000.0);
    CHECK(f.law.k_normal / f.law.k_tangential == doctest::Approx(0.4).epsilon(1e-12));
    // Switching to the model in use changes nothing.
    const ForceDef before = f;
    set_force_model(f, ForceModel::ellipsoid);
    CHECK(f.law.k_tangential == before.law.k_tangential);
}

TEST_CASE("ellipsoid field: a field angle turns its axes (seed 004's alpha), 90 deg swaps k_t and k_n") {
    const Vec2 n{0.0, 1.0};
    const double kt = 1200.0, kn = 480.0;  // e = 0.4: the k_normal axis is the compliant one (a1)
    for (const Vec2 p : {Vec2{0.001, -0.002}, Vec2{-0.003, -0.0005}, Vec2{0.0015, -0.0015}}) {
        // A quarter turn puts the k_normal axis along the tangent: the same as swapping them.
        const Vec2 turned = ellipsoid_force(p, n, kt, kn, 0.5 * kPi), swapped = ellipsoid_force(p, n, kn, kt);
        CHECK(glm::length(turned - swapped) <= 1e-12 * glm::length(swapped));
        // Seed 004: a1 at alpha = 45 deg (field angle -45 deg) or 135 deg (+45 deg). Pressing
        // along a1 meets k_normal alone: |F| = kn |p|; across it, kt |p|.
        const double a = 0.25 * kPi;
        const Vec2 along_a1{std::cos(a), std::sin(a)};  // 45 deg from the surface tangent (+x)
        const Vec2 f45 = ellipsoid_force(-0.002 * along_a1, n, kt, kn, a - 0.5 * kPi);
        CHECK(glm::length(f45) == doctest::Approx(kn * 0.002).epsilon(1e-12));
        const Vec2 f135 = ellipsoid_force(-0.002 * along_a1, n, kt, kn, 0.75 * kPi - 0.5 * kPi);
        CHECK(glm::length(f135) == doctest::Approx(kt * 0.002).epsilon(1e-12));
    }
}

TEST_CASE("ellipsoid field: field_angle reads, round-trips and is refused beyond pi") {
    const std::string base = R"({"version": 1, "contours": [], "force": {"model": "ellipsoid", "k_tangential": 1200,
        "k_normal": 480, "max_force": 1.5, "field_angle": )";
    const Scene s = parse_scene(base + "-0.7853981633974483}}");
    CHECK(s.force.law.field_angle == -0.7853981633974483);
    CHECK(parse_scene(scene_to_json_text(s)).force.law.field_angle == s.force.law.field_angle);
    CHECK_THROWS_WITH_AS(parse_scene(base + "4}}"), "scene: force.field_angle: must lie in [-pi, pi] rad, got 4", SceneError);
}
