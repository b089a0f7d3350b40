// test_geometry_extremes.cpp — the finger and the contour at the ends of what a scene may hold:
// pad radius 1e-4 m to 1 m, pad length up to nearly the whole circle, segments of 1e-9 m,
// coincident and collinear curve control points, coordinates 1e3 m and 1e6 m from the origin,
// finger angles of +-1e3 rad. Each against its analytic answer, or against the same motion at the
// origin / at the wrapped angle, with tolerances from the double spacing of the coordinates.
#include "extremes_fixture.hpp"
#include "scene_builders.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

using namespace contactlab;
using namespace contactlab::extremes;

namespace {

// Lowers a finger (phi, rad) onto the floor y = origin.y from 1 mm above the pad's lowest point
// down to `depth` (m) below it, in 20 steps, and returns the last output.
ProxyOutput press_floor(Rig& rig, Vec2 origin, double radius, double depth, double phi = 0.0) {
    const Vec2 touching = origin + Vec2{0.0, radius};
    rig.proxy->reset(touching + Vec2{0.0, 0.001}, phi);
    ProxyOutput out;
    for (int k = 1; k <= 20; ++k) {
        const double d = -0.001 + (depth + 0.001) * k / 20.0;
        out = rig.at(touching - Vec2{0.0, d}, phi);
    }
    return out;
}

}  // namespace

TEST_CASE("pad radius from 1e-4 m to 1 m, pad length up to nearly 2 pi R: a floor pushes Ke d straight up") {
    for (double radius : {1e-4, 1e-3, kNominalRadius, 0.1, 1.0}) {
        for (double length_fraction : {1e-3, 0.1, 0.5, 1.0 - 1e-9}) {  // of the whole circle, 2 pi R
            const double length = length_fraction * 2.0 * kPi * radius;
            for (double depth : {1e-8, 1e-6, 1e-3, 0.01}) {
                CAPTURE(radius);
                CAPTURE(length);
                CAPTURE(depth);
                Rig rig(floor_at({0.0, 0.0}), def_with(radius, length));
                const ProxyOutput out = press_floor(rig, {0.0, 0.0}, radius, depth);
                check_usable(out, kNominalMaxForce);
                REQUIRE(out.contact);
                const double expected = std::min(kNominalStiffness * depth, kNominalMaxForce);
                // The depth is a difference of coordinates of size R: good to a few ulp(R).
                CHECK(std::abs(out.force.y - expected) <= kNominalStiffness * position_tolerance(radius) + 1e-12 * expected);
                CHECK(std::abs(out.force.x) <= kNominalStiffness * position_tolerance(1.0));
                CHECK(std::abs(out.proxy.y - radius) <= position_tolerance(radius));
                // The pad's midpoint touches: l_d = 0 whatever R and L.
                CHECK(std::abs(out.l_d) <= position_tolerance(radius));
            }
        }
    }
}

TEST_CASE("a pad of nearly the whole circle slides over the block's corners with finite, clamped force") {
    for (double radius : {1e-4, kNominalRadius, 1.0}) {
        const double length = (1.0 - 1e-9) * 2.0 * kPi * radius;
        Rig rig(block_at({0.0, 0.0}), def_with(radius, length));
        // Along the top 1 mm deep, over both corners and down to the floor on either side.
        rig.proxy->reset({-0.25, radius + 0.01}, 0.0);
        int contacts = 0;
        for (int k = 0; k <= 2000; ++k) {
            const double x = -0.25 + 0.5 * k / 2000.0;
            const double top = std::abs(x) < 0.05 ? 0.06 : 0.0;
            const ProxyOutput& out = rig.at({x, top + radius - 0.001}, 0.0);
            check_usable(out, kNominalMaxForce);
            contacts += out.contact ? 1 : 0;
        }
        CAPTURE(radius);
        CHECK(contacts > 0);
    }
}

TEST_CASE("segments of 1e-9 m: a nanometre step and a nanometre segment in a floor change the force by Ke x 1 nm") {
    // Floor y = 0 up to x = 0, a 1e-9 m step up, a 1e-9 m segment, then the floor y = 1e-9 m.
    constexpr double nm = 1e-9;  // m
    Scene s;
    Contour c;
    c.segments = {line({-0.3, 0.0}, {0.0, 0.0}), line({0.0, 0.0}, {0.0, nm}), line({0.0, nm}, {nm, nm}),
                  line({nm, nm}, {0.3, nm})};
    s.contours.push_back(c);
    Rig rig(s, def_with(kNominalRadius, kNominalLength));
    const double depth = 0.001;  // m below y = 0
    rig.proxy->reset({-0.05, kNominalRadius + 0.01}, 0.0);
    for (int k = 0; k <= 1000; ++k) {
        const double x = -0.05 + 0.1 * k / 1000.0;
        const ProxyOutput& out = rig.at({x, kNominalRadius - depth}, 0.0);
        check_usable(out, kNominalMaxForce);
        REQUIRE(out.contact);
        // Depth below whichever floor level the pad rests on: between d and d + 1 nm.
        CHECK(out.force.y >= kNominalStiffness * depth - kNominalStiffness * 1e-12);
        CHECK(out.force.y <= kNominalStiffness * (depth + nm) + kNominalStiffness * 1e-12);
        // Within sqrt(2 R nm) of the step the proxy rides the step corner's c-space circle
        // (radius R), so the force tilts by at most that over R.
        CHECK(std::abs(out.force.x) <= 1.01 * glm::length(out.force) * std::sqrt(2.0 * nm / kNominalRadius));
    }
}

TEST_CASE("a thousand 1e-9 m segments zigzagging under the pad: finite, clamped, no tunnelling") {
    // A 0.6 um wide patch of zigzag teeth of 1 nm segments, in the middle of a floor.
    constexpr double nm = 1e-9;  // m
    Scene s;
    Contour c;
    Vec2 p{-0.3, 0.0};
    c.segments.push_back(line(p, {0.0, 0.0}));
    p = {0.0, 0.0};
    for (int i = 0; i < 1000; ++i) {
        const Vec2 q = p + Vec2{0.6 * nm, (i % 2 == 0 ? 1.0 : -1.0) * 0.8 * nm};  // 1 nm long
        c.segments.push_back(line(p, q));
        p = q;
    }
    c.segments.push_back(line(p, {0.3, p.y}));
    s.contours.push_back(c);
    Rig rig(s, def_with(kNominalRadius, kNominalLength));
    rig.proxy->reset({-0.02, kNominalRadius + 0.01}, 0.0);
    for (int k = 0; k <= 400; ++k) {
        const double x = -0.02 + 0.04 * k / 400.0;
        const ProxyOutput& out = rig.at({x, kNominalRadius - 0.001}, 0.0);
        check_usable(out, kNominalMaxForce);
        // The teeth stand at most 0.8 nm proud: the proxy stays on top of the floor.
        CHECK(out.proxy.y >= kNominalRadius - 1e-12);
        CHECK(out.proxy.y <= kNominalRadius + 0.8 * nm + 1e-12);
    }
}

TEST_CASE("coincident and collinear control points: a straight Bezier is a floor, exact and flattened") {
    // Each of these curves runs along y = 0 through x = 0 (some with cusps where they reverse).
    const std::vector<Segment> straight_curves = {
        QuadSegment{{-0.3, 0.0}, {-0.3, 0.0}, {0.3, 0.0}},                  // p1 on p0
        QuadSegment{{-0.3, 0.0}, {0.3, 0.0}, {0.3, 0.0}},                   // p1 on p2
        CubicSegment{{-0.3, 0.0}, {-0.3, 0.0}, {0.3, 0.0}, {0.3, 0.0}},     // p1 on p0, p2 on p3
        CubicSegment{{-0.3, 0.0}, {0.1, 0.0}, {0.1, 0.0}, {0.3, 0.0}},      // p1 on p2
    };
    for (CurveMode mode : {CurveMode::exact, CurveMode::flatten}) {
        for (std::size_t i = 0; i < straight_curves.size(); ++i) {
            CAPTURE(i);
            CAPTURE(static_cast<int>(mode));
            Scene s;
            s.curves.mode = mode;
            s.curves.tolerance = 1e-6;
            Contour c;
            c.segments.push_back(straight_curves[i]);
            s.contours.push_back(c);
            Rig rig(s, proxy_def_of(s));
            // The exact mode is an arc spline within 1e-10 m of the curve; a chord of a straight
            // curve is the curve itself.
            const double geometry_tol = 1e-10;  // m
            rig.proxy->reset({-0.1, kNominalRadius + 0.01}, 0.0);
            for (int k = 0; k <= 200; ++k) {
                const double x = -0.1 + 0.2 * k / 200.0;
                const ProxyOutput& out = rig.at({x, kNominalRadius - 0.001}, 0.0);
                check_usable(out, kNominalMaxForce);
                REQUIRE(out.contact);
                CHECK(std::abs(out.force.y - 1.0) <= kNominalStiffness * geometry_tol);
                CHECK(std::abs(out.force.x) <= kNominalStiffness * geometry_tol);
            }
        }
    }
}

TEST_CASE("a collinear cubic that reverses twice: finite, clamped, pushing out of the floor") {
    // The curve runs right, back left past its start, then right again along y = 0. Solid lies on
    // the right of travel, so the backward run claims the other side: a zero-thickness overlap
    // with no analytic answer. What must hold is that the proxy copes: finite and clamped.
    for (CurveMode mode : {CurveMode::exact, CurveMode::flatten}) {
        Scene s;
        s.curves.mode = mode;
        s.curves.tolerance = 1e-6;
        Contour c;
        c.segments.push_back(CubicSegment{{-0.3, 0.0}, {0.5, 0.0}, {-0.5, 0.0}, {0.3, 0.0}});
        s.contours.push_back(c);
        Rig rig(s, proxy_def_of(s));
        rig.proxy->reset({-0.1, kNominalRadius + 0.01}, 0.0);
        for (int k = 0; k <= 200; ++k) {
            const ProxyOutput& out = rig.at({-0.1 + 0.2 * k / 200.0, kNominalRadius - 0.001}, 0.0);
            check_usable(out, kNominalMaxForce);
            CHECK(glm::length(out.force) <= kNominalStiffness * 0.001 * (1.0 + 1e-9));
        }
    }
}

TEST_CASE("a press shallower than 1e-9 m is touching, not pressing, so contact does not flicker with rounding") {
    Rig rig(floor_at({0.0, 0.0}), def_with(kNominalRadius, kNominalLength));
    rig.proxy->reset({0.0, kNominalRadius + 0.001}, 0.0);
    const ProxyOutput touching = rig.at({0.0, kNominalRadius - 5e-10}, 0.0);
    CHECK_FALSE(touching.contact);
    CHECK(glm::length(touching.force) == 0.0);
    const ProxyOutput& pressing = rig.at({0.0, kNominalRadius - 1e-8}, 0.0);
    CHECK(pressing.contact);
    CHECK(pressing.force.y == doctest::Approx(kNominalStiffness * 1e-8).epsilon(1e-6));
}

TEST_CASE("coordinates 1e3 m and 1e6 m from the origin: the block feels the same as at the origin") {
    for (double distance : {1e3, 1e6}) {
        for (Vec2 direction : {Vec2{1.0, 0.0}, Vec2{-0.6, 0.8}}) {
            const Vec2 shift = distance * direction;
            CAPTURE(distance);
            Rig here(block_at({0.0, 0.0}), def_with(kNominalRadius, kNominalLength));
            Rig there(block_at(shift), def_with(kNominalRadius, kNominalLength));
            const double tol = position_tolerance(distance);  // m
            here.proxy->reset({-0.25, kNominalRadius + 0.01}, 0.0);
            there.proxy->reset(shift + Vec2{-0.25, kNominalRadius + 0.01}, 0.0);
            for (int k = 0; k <= 1000; ++k) {
                const double x = -0.25 + 0.5 * k / 1000.0;
                const double top = std::abs(x) < 0.05 ? 0.06 : 0.0;
                const double phi = 0.3 * std::sin(k * 0.01);  // rad: rock the finger as it goes
                const Vec2 f{x, top + kNominalRadius - 0.001};
                const ProxyOutput a = here.at(f, phi);
                const ProxyOutput& b = there.at(shift + f, phi);
                check_usable(b, kNominalMaxForce);
                REQUIRE(a.contact == b.contact);
                CHECK(glm::length((b.proxy - shift) - a.proxy) <= tol);
                CHECK(glm::length(b.force - a.force) <= kNominalStiffness * tol);
                // A contact location moves with the contact point along the pad: the same tolerance.
                CHECK(std::abs(b.l_d - a.l_d) <= tol);
            }
        }
    }
}

TEST_CASE("finger angle at +-1e3 rad: the same contact as the wrapped angle") {
    Rig wrapped(block_at({0.0, 0.0}), def_with(kNominalRadius, kNominalLength));
    for (double base : {1e3, -1e3}) {
        // A whole number of turns near +-1000 rad, so the pad faces down as at phi = 0.
        const double turns = std::round(base / (2.0 * kPi)) * 2.0 * kPi;
        Rig far(block_at({0.0, 0.0}), def_with(kNominalRadius, kNominalLength));
        wrapped.proxy->reset({-0.25, kNominalRadius + 0.01}, 0.0);
        far.proxy->reset({-0.25, kNominalRadius + 0.01}, turns);
        // phi is stored to ulp(1e3) = 1.1e-13 rad; the pad's points move by R times that.
        const double tol = position_tolerance(1e3);
        for (int k = 0; k <= 1000; ++k) {
            const double x = -0.25 + 0.5 * k / 1000.0;
            const double top = std::abs(x) < 0.05 ? 0.06 : 0.0;
            const double rock = 0.3 * std::sin(k * 0.01);  // rad
            const Vec2 f{x, top + kNominalRadius - 0.001};
            const ProxyOutput a = wrapped.at(f, rock);
            const ProxyOutput& b = far.at(f, turns + rock);
            check_usable(b, kNominalMaxForce);
            CAPTURE(base);
            CAPTURE(k);
            REQUIRE(a.contact == b.contact);
            CHECK(glm::length(b.proxy - a.proxy) <= tol);
            CHECK(glm::length(b.force - a.force) <= kNominalStiffness * tol);
            CHECK(std::abs(b.l_d - a.l_d) <= tol);
        }
    }
}

TEST_CASE("the finger spun by 1e3 rad in one tick while pressed into a floor: finite, clamped, not through") {
    Rig rig(floor_at({0.0, 0.0}), def_with(kNominalRadius, kNominalLength));
    rig.proxy->reset({0.0, kNominalRadius + 0.001}, 0.0);
    const Vec2 pressed{0.0, kNominalRadius - 0.001};
    rig.at(pressed, 0.0);
    for (double phi : {1e3, -1e3, 0.5, 1e3 + 0.5, 0.0}) {
        const ProxyOutput& out = rig.at(pressed, phi);
        CAPTURE(phi);
        check_usable(out, kNominalMaxForce);
        // Whatever the pad faces, no point of the pad around the proxy lies below the floor: the
        // finger did not pass through.
        const double half = pad_half_angle(rig.proxy->def().finger);
        for (int i = 0; i <= 100; ++i) {
            const double theta = pad_mid_angle(out.phi) - half + 2.0 * half * i / 100.0;
            CHECK(out.proxy.y + kNominalRadius * std::sin(theta) >= -position_tolerance(1e3));
        }
    }
}

TEST_CASE("a jump across 20,000 segments and a half-turn of the finger in one tick: the work stops at its bounds") {
    // A 0.4 m sinusoid (1 cm amplitude, 50 periods) in 20,000 chords of ~27 um each.
    Scene s;
    s.contours.push_back(test::sinusoid_contour(20000, 0.01, 50.0));
    Rig rig(s, def_with(kNominalRadius, kNominalLength));
    rig.proxy->reset({-0.19, 0.05}, 0.0);
    rig.at({-0.19, 0.0}, 0.0);
    // Along the whole contour in one tick, pressed in: thousands of vertices to slide over.
    const ProxyOutput jump = rig.at({0.19, 0.0}, 0.0);
    check_usable(jump, kNominalMaxForce);
    CHECK(jump.work.walk_steps == kProxyMaxWalkSteps);  // the cap is what stopped it
    // The proxy catches up over the following ticks, each again within its bounds.
    ProxyOutput out = jump;
    int ticks = 0;
    while (out.work.walk_steps == kProxyMaxWalkSteps && ticks < 1000) {
        out = rig.at({0.19, 0.0}, 0.0);
        check_usable(out, kNominalMaxForce);
        ++ticks;
    }
    CHECK(ticks < 1000);
    CHECK(out.work.walk_steps < kProxyMaxWalkSteps);
    CHECK(out.contact);
    // Half a turn while pressed among the 27 um features: the re-projection sub-steps (a quarter
    // of the smallest feature each) hit their cap, and the tick still ends usable.
    const ProxyOutput turned = rig.at({0.19, 0.0}, kPi);
    check_usable(turned, kNominalMaxForce);
    CHECK(turned.work.rotation_steps == kProxyMaxRotationSteps);
}
