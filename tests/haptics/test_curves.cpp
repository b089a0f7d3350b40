// test_curves.cpp — Bezier segments: the curve tools (nearest point, conversion) and the proxy's
// contact with curves, exact by default and flattened on request.
#include "scene_builders.hpp"

#include "haptics/bezier.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/stimuli.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace contactlab;
using namespace contactlab::test;

namespace {

constexpr double R = 0.026;  // m
constexpr double L = 0.020;  // m

// The parabola y = 10 x^2 for x in [-0.1, 0.1] m as ONE quadratic segment, travelled left to right
// (solid below): curvature radius 5 cm at the bottom, wider than the pad, so the pad's interior
// touches it at one point.
const QuadSegment kParabola{{-0.1, 0.1}, {0.0, -0.1}, {0.1, 0.1}};

// Reference geometry of y = 10 x^2 in long double: the point at x, its free-side (upward) unit
// normal.
struct RefPoint {
    long double x, y, nx, ny;
};
RefPoint parabola_ref(long double x) {
    const long double slope = 20.0L * x;
    const long double len = std::sqrt(1.0L + slope * slope);
    return {x, 10.0L * x * x, -slope / len, 1.0L / len};
}

Scene curve_scene(const Segment& s, CurveMode mode = CurveMode::exact, double tolerance = 1e-4) {
    Scene scene;
    Contour c;
    c.segments.push_back(s);
    scene.contours.push_back(c);
    scene.curves.mode = mode;
    scene.curves.tolerance = tolerance;
    return scene;
}

}  // namespace

TEST_CASE("nearest point on a quadratic matches a brute-force search") {
    const Bezier b = segment_bezier(Segment{kParabola});
    for (const Vec2 q : {Vec2{0.01, 0.03}, Vec2{-0.07, 0.2}, Vec2{0.0, -0.05}, Vec2{0.3, 0.0}, Vec2{0.05, 0.025}}) {
        const CurveFoot foot = bezier_nearest(b, q);
        double brute = 1e9;
        for (int i = 0; i <= 200000; ++i) brute = std::min(brute, glm::length(bezier_point(b, i / 200000.0) - q));
        CAPTURE(q.x);
        CAPTURE(q.y);
        CHECK(foot.distance <= brute + 1e-15);
        CHECK(foot.distance >= brute - 1e-9);  // brute force samples every 1e-6 of s: ~1e-12 m apart
    }
}

TEST_CASE("arc spline and polyline stay within their tolerance of the curve") {
    const Bezier quad = segment_bezier(Segment{kParabola});
    const Bezier cubic{3, {Vec2{0, 0}, Vec2{0.03, 0.04}, Vec2{0.06, -0.04}, Vec2{0.1, 0.0}}};
    for (const Bezier* b : {&quad, &cubic}) {
        std::vector<CurvePiece> arcs, lines;
        bezier_to_arcs(*b, kExactCurveTolerance, arcs);
        bezier_to_lines(*b, 1e-4, lines);
        CHECK(curve_pieces_max_error(*b, arcs, 20000) <= 1.5 * kExactCurveTolerance);
        CHECK(curve_pieces_max_error(*b, lines, 20000) <= 1e-4 * 1.01);
        // G1: consecutive arcs share end points and tangents.
        for (std::size_t i = 1; i < arcs.size(); ++i) CHECK(glm::length(arcs[i].from - arcs[i - 1].to) == 0.0);
    }
}

TEST_CASE("parabola as one quad segment: pad interior contact matches the exact offset curve") {
    ProxyRig rig(curve_scene(kParabola));
    int checked = 0;
    for (long double x = -0.06L; x <= 0.06L; x += 0.004L) {
        const RefPoint p = parabola_ref(x);
        // Finger angle chosen so the contact sits 4 mm proximal of the pad's middle.
        const long double theta = std::atan2(-p.ny, -p.nx);  // pad angle of the contact point
        const double l_expected = -0.004;
        const double phi = static_cast<double>(theta + 0.5L * std::acos(-1.0L)) - l_expected / R;
        const double depth = 0.001;
        const Vec2 finger{static_cast<double>(p.x + (R - depth) * p.nx), static_cast<double>(p.y + (R - depth) * p.ny)};
        const Vec2 expected{static_cast<double>(p.x + R * p.nx), static_cast<double>(p.y + R * p.ny)};
        // Approach along the normal from free space, as a user pressing straight in.
        rig.proxy->reset(finger + 0.05 * Vec2{static_cast<double>(p.nx), static_cast<double>(p.ny)}, phi);
        const ProxyOutput& o = rig.at(finger, phi);
        CAPTURE(static_cast<double>(x));
        REQUIRE(o.contact);
        CAPTURE(o.contacts[0].point);
        CAPTURE(o.contacts[1].point);
        CAPTURE(static_cast<int>(o.contacts[0].source));
        CAPTURE(static_cast<int>(o.contacts[1].source));
        CAPTURE(o.contacts[1].l);
        CHECK(o.contact_count == 1);
        CHECK(glm::length(o.proxy - expected) <= 1e-9);
        CHECK(std::abs(o.depth - depth) <= 1e-9);
        CHECK(std::abs(o.l_d - l_expected) <= 1e-9);
        CHECK(glm::length(o.force - 1000.0 * (o.proxy - finger)) <= 1e-9);
        ++checked;
    }
    CHECK(checked == 31);
}

TEST_CASE("sliding along a chain of G1 quads keeps force and contact location continuous") {
    // A wavy floor of 8 quadratic segments joined G1: each control point mirrors the previous
    // one about the joint, so tangents agree there.
    Contour c;
    Vec2 p0{-0.16, 0.0}, p1{-0.14, 0.01};
    for (int i = 0; i < 8; ++i) {
        const Vec2 p2{p0.x + 0.04, 0.0};
        c.segments.push_back(QuadSegment{p0, p1, p2});
        p1 = p2 + (p2 - p1);
        p0 = p2;
    }
    Scene scene;
    scene.contours.push_back(c);
    ProxyRig rig(scene);
    rig.proxy->reset({-0.12, 0.1}, 0.0);
    const double step = 1e-5;  // m per tick
    double prev_f = -1.0, prev_l = 0.0, worst_df = 0.0, worst_dl = 0.0;
    for (double x = -0.12; x <= 0.12; x += step) {
        // x is linear in s on each quad (p1 sits midway in x), so the height under x is exact.
        const std::size_t k = static_cast<std::size_t>((x + 0.16) / 0.04);
        const Bezier b = segment_bezier(c.segments[k]);
        const double y = bezier_point(b, (x - b.p[0].x) / 0.04).y;
        const ProxyOutput& o = rig.at({x, y + R - 0.002}, 0.0);
        REQUIRE(o.contact);
        const double mag = glm::length(o.force);
        if (prev_f >= 0.0) {
            worst_df = std::max(worst_df, std::abs(mag - prev_f));
            worst_dl = std::max(worst_dl, std::abs(o.l_d - prev_l));
        }
        prev_f = mag;
        prev_l = o.l_d;
    }
    // The surface height changes by at most |slope| * step per tick (slope <= 0.5 here), so depth
    // and force (Ke = 1000 N/m) change by at most 1000 * 0.5 * 1e-5 = 5 mN per tick; the contact
    // point moves by a few steps' worth along the pad. A joint artefact would show as a jump.
    CHECK(worst_df <= 0.005);
    CHECK(worst_dl <= 50 * step);
    MESSAGE("worst |F| step " << worst_df << " N, worst l_d step " << worst_dl << " m");
}

TEST_CASE("degenerate control points give finite, touchable curves") {
    struct Case {
        std::string name;
        Segment s;
    };
    const Case cases[] = {
        {"collinear (a straight quad)", QuadSegment{{-0.1, 0.0}, {0.0, 0.0}, {0.1, 0.0}}},
        {"p1 = p0", QuadSegment{{-0.1, 0.0}, {-0.1, 0.0}, {0.1, 0.0}}},
        {"p1 = p2", QuadSegment{{-0.1, 0.0}, {0.1, 0.0}, {0.1, 0.0}}},
        {"reversal (p1 beyond p2)", QuadSegment{{-0.1, 0.0}, {0.2, 0.0}, {0.1, 0.0}}},
        {"cubic with a cusp", CubicSegment{{-0.1, 0.0}, {0.1, 0.05}, {-0.1, 0.05}, {0.1, 0.0}}},
        {"cubic with p1 = p2", CubicSegment{{-0.1, 0.0}, {0.0, 0.02}, {0.0, 0.02}, {0.1, 0.0}}},
    };
    for (const Case& k : cases) {
        CAPTURE(k.name);
        for (CurveMode mode : {CurveMode::exact, CurveMode::flatten}) {
            ProxyRig rig(curve_scene(k.s, mode));
            for (const EnvSegment& e : rig.env.segments) {
                REQUIRE(is_finite(e.start));
                REQUIRE(is_finite(e.end));
                REQUIRE(std::isfinite(e.length));
            }
            // Press down 1 mm onto the curve at x = -0.05 m from high above: contact, finite force.
            rig.proxy->reset({-0.05, 0.2}, 0.0);
            const ProxyOutput& o = rig.at({-0.05, -0.05}, 0.0);
            REQUIRE(is_finite(o.proxy));
            REQUIRE(is_finite(o.force));
            CHECK(o.contact);
            CHECK(o.proxy.y >= -0.05);
        }
    }
}

TEST_CASE("flatten mode: the proxy's error is bounded by the chord tolerance") {
    for (const double tol : {1e-3, 1e-4, 1e-5}) {
        ProxyRig exact(curve_scene(kParabola)), flat(curve_scene(kParabola, CurveMode::flatten, tol));
        double worst = 0.0;
        for (double x = -0.015; x <= 0.015; x += 0.0005) {
            const RefPoint p = parabola_ref(x);
            const Vec2 finger{x, static_cast<double>(p.y) + R - 0.001};  // 1 mm deep
            exact.proxy->reset(finger + Vec2{0.0, 0.05}, 0.0);
            flat.proxy->reset(finger + Vec2{0.0, 0.05}, 0.0);
            const Vec2 a = exact.at(finger, 0.0).proxy;
            const Vec2 b = flat.at(finger, 0.0).proxy;
            worst = std::max(worst, glm::length(a - b));
        }
        CAPTURE(tol);
        // Every chord lies within tol of the curve, so the offset obstacle moves by at most tol
        // along the normal (over |slope| <= 0.3 the pad's middle touches: factor 1/cos <= 1.05).
        // Frictionless, the proxy is the finger's foot on the obstacle, and a chord's normal is
        // off the curve's by up to half the chord's turn, sqrt(2 tol kappa) for a chord within
        // tol on curvature kappa (<= 20 1/m here): at depth d the foot slides by d times that.
        const double depth = 0.001;
        CHECK(worst <= 1.05 * tol + depth * std::sqrt(2.0 * tol * 20.0));
        CHECK(worst > 0.0);
        MESSAGE("flatten tolerance " << tol << " m: worst proxy difference from exact " << worst << " m");
    }
}

TEST_CASE("scene files hold quad and cubic segments and the curve mode") {
    Scene s;
    Contour c;
    c.segments.push_back(QuadSegment{{-0.1, 0.0}, {-0.05, 0.03}, {0.0, 0.0}});
    c.segments.push_back(CubicSegment{{0.0, 0.0}, {0.1 / 3.0, -0.02}, {0.2 / 3.0, 0.02}, {0.1, 0.0}});
    s.contours.push_back(c);
    s.curves = {CurveMode::flatten, 2.5e-5};
    const Scene back = parse_scene(scene_to_json_text(s), "curves.json");
    REQUIRE(back.contours.size() == 1);
    REQUIRE(back.contours[0].segments.size() == 2);
    const auto& q = std::get<QuadSegment>(back.contours[0].segments[0]);
    const auto& k = std::get<CubicSegment>(back.contours[0].segments[1]);
    CHECK(q.p1 == Vec2{-0.05, 0.03});
    CHECK(k.p1 == Vec2{0.1 / 3.0, -0.02});
    CHECK(k.p2 == Vec2{0.2 / 3.0, 0.02});
    CHECK(back.curves.mode == CurveMode::flatten);
    CHECK(back.curves.tolerance == 2.5e-5);

    auto error_of = [](const std::string& text) {
        try {
            parse_scene(text, "t.json");
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string head = R"({"version": 1, "contours": [{"closed": false, "segments": [)";
    CHECK(error_of(head + R"({"type": "quad", "p0": [0, 0], "p1": [1, 1e999], "p2": [2, 0]}]}]})")
              .find("t.json: contours[0].segments[0].p1[1]: not a finite number") != std::string::npos);
    CHECK(error_of(head + R"({"type": "quad", "p0": [0, 0], "p1": [0, 0], "p2": [0, 0]}]}]})")
              .find("t.json: contours[0].segments[0]: zero-length curve") != std::string::npos);
    CHECK(error_of(head + R"({"type": "cubic", "p0": [0, 0], "p1": [0, 1], "p2": [1, 1]}]}]})")
              .find("t.json: contours[0].segments[0].p3: missing") != std::string::npos);
    CHECK(error_of(head + R"({"type": "line", "from": [0, 0], "to": [1, 0]}]}], "curves": {"mode": "fast"}})")
              .find("t.json: curves.mode: unknown curve mode \"fast\"") != std::string::npos);
    CHECK(error_of(head + R"({"type": "line", "from": [0, 0], "to": [1, 0]}]}], "curves": {"mode": "flatten", "tolerance": 0}})")
              .find("t.json: curves.tolerance: must lie in") != std::string::npos);
}

// Seed 002's stimulus itself: slide 1 mm deep (along the normal) over a generated bumps scene in
// exact mode and compare what happens at the G1 joints between its quadratic segments with what
// happens inside them. A joint artefact (a missed handover, a re-solve landing on the wrong
// segment) would show as a step at a joint far above the steps inside the curves.
TEST_CASE("generated bumps: |F| and l_d are as continuous across G1 joints as inside the curves") {

    const GeneratedScene g = generate_bumps(BumpsDef{});
    Scene scene = g.scene;
    scene.force.max_force = 100.0;  // N: no clamping, so |F| = Ke depth shows everything
    ProxyRig rig(scene);
    // Pass 1: a finger far below the envelope drags the proxy along the c-space boundary; pass 2
    // puts the finger 1 mm inside along that boundary's normal.
    std::vector<Vec2> fingers;
    {
        ProxyRig guide(scene);
        const auto& env = g.envelope;
        std::size_t j = 0;
        guide.proxy->reset({0.005, 0.3}, 0.0);
        for (double x = 0.005; x <= 0.175; x += 2e-5) {
            while (j + 2 < env.size() && env[j + 1].x < x) ++j;
            const double t = (x - env[j].x) / (env[j + 1].x - env[j].x);
            const Vec2 f{x, env[j].y + t * (env[j + 1].y - env[j].y) + R - 0.003};
            const ProxyOutput& o = guide.at(f, 0.0);
            if (o.contact_count == 1 && o.depth > 0.0) fingers.push_back(o.proxy - 0.001 * (o.proxy - f) / o.depth);
        }
    }
    REQUIRE(fingers.size() > 5000);
    rig.proxy->reset(fingers[0] + Vec2{0.0, 0.05}, 0.0);
    std::vector<double> inside_df, inside_dl, joint_df, joint_dl;  // per unit finger motion
    ProxyOutput last;
    for (std::size_t k = 0; k < fingers.size(); ++k) {
        const ProxyOutput& o = rig.at(fingers[k], 0.0);
        if (k > 0 && o.contact_count == 1 && last.contact_count == 1) {
            const double moved = glm::length(fingers[k] - fingers[k - 1]);
            const double df = std::abs(glm::length(o.force) - glm::length(last.force)) / moved;
            const double dl = std::abs(o.l_d - last.l_d) / moved;
            const int a = rig.env.segments[static_cast<std::size_t>(last.contacts[0].segment)].scene_segment;
            const int b = rig.env.segments[static_cast<std::size_t>(o.contacts[0].segment)].scene_segment;
            if (a == b) {
                inside_df.push_back(df);
                inside_dl.push_back(dl);
            } else if (std::abs(a - b) == 1) {
                joint_df.push_back(df);
                joint_dl.push_back(dl);
            }
        }
        last = o;
    }
    REQUIRE(joint_df.size() >= 20);  // the stroke crosses dozens of joints
    std::sort(inside_df.begin(), inside_df.end());
    std::sort(inside_dl.begin(), inside_dl.end());
    const double df_ref = inside_df[inside_df.size() * 999 / 1000];
    const double dl_ref = inside_dl[inside_dl.size() * 999 / 1000];
    const double df_joint = *std::max_element(joint_df.begin(), joint_df.end());
    const double dl_joint = *std::max_element(joint_dl.begin(), joint_dl.end());
    MESSAGE("joints crossed " << joint_df.size() << "; d|F|/dx: joints max " << df_joint << ", inside p99.9 "
            << df_ref << " N/m; dl_d/dx: joints max " << dl_joint << ", inside p99.9 " << dl_ref);
    // |F| = Ke depth with the depth held at 1 mm, so |F| barely moves (a missed handover would
    // give ~Ke = 1000 N/m); l_d follows the normal's turn, R kappa per unit length. A joint may
    // not exceed twice the worst seen inside a curve.
    CHECK(df_joint <= 2.0 * std::max(df_ref, 1e-3));
    CHECK(dl_joint <= 2.0 * std::max(dl_ref, 1e-6));
}
