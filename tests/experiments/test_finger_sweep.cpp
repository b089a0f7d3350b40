// test_finger_sweep.cpp — seed 003's live sweep (drivers/finger_sweep.hpp): where the finger's
// circle rests on the arc stimulus, against a brute force over the generated scene's points
// (experiments::resting_height, written without the sweep's geometry); the pass's ends and
// timing; and each live trial's sweep from the protocol (LiveSession::sweep()).
#include "drivers/finger_sweep.hpp"
#include "engine/experiments/runs/live_session.hpp"
#include "engine/experiments/protocol/surface_profile.hpp"
#include "haptics/stimuli.hpp"
#include "process.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <variant>
#include <vector>

using namespace contactlab;
using cli_test::TempDir;

namespace {

// The generated arc scene's contour as points every 0.02 mm along it.
experiments::SurfaceProfile arc_points(double chord, double height) {
    const Scene s = generate_arc(chord, height);
    std::vector<Vec2> pts;
    for (const Segment& seg : s.contours.at(0).segments) {
        const int n = static_cast<int>(std::ceil(segment_length(seg) / 2e-5));
        for (int i = 0; i <= n; ++i) {
            const double u = static_cast<double>(i) / n;
            if (const auto* l = std::get_if<LineSegment>(&seg)) {
                pts.push_back(l->from + (l->to - l->from) * u);
            } else {
                const auto& a = std::get<ArcSegment>(seg);
                const double ang = a.start_angle + (a.end_angle - a.start_angle) * u;
                pts.push_back(a.center + a.radius * Vec2{std::cos(ang), std::sin(ang)});
            }
        }
    }
    return experiments::profile_of(std::move(pts));
}

}  // namespace

TEST_CASE("finger sweep: the finger rests on the arc where a brute force over its points puts it, floor, corners and cap") {
    // Points 0.02 mm apart: the brute force's circle sits at most the sag of a 0.02 mm chord
    // (under 1e-8 m on the 10 mm finger and the arcs' 0.4-1.1 m radii) below the true one; 1e-7 m
    // covers it. Across the floor (R above it), over the corners and the cap.
    for (const double height : {0.010, 0.020, 0.030}) {
        drivers::FingerSweep s;
        s.chord = 0.30;
        s.height = height;
        s.finger_radius = 0.010;
        const experiments::SurfaceProfile pts = arc_points(s.chord, s.height);
        std::size_t hint = 0;
        double worst = 0.0;
        for (double x = -0.17; x <= 0.17; x += 0.00037) {
            const double brute = experiments::resting_height(pts, x, s.finger_radius, hint);
            worst = std::max(worst, std::abs(drivers::finger_sweep_resting_height(s, x) - brute));
        }
        CAPTURE(height);
        CHECK(worst < 1e-7);
        // The top: R above the arc's apex; the floor: R above it.
        CHECK(drivers::finger_sweep_resting_height(s, 0.0) == doctest::Approx(height + s.finger_radius).epsilon(1e-12));
        CHECK(drivers::finger_sweep_resting_height(s, 0.17) == doctest::Approx(s.finger_radius).epsilon(1e-12));
    }
}

TEST_CASE("finger sweep: down onto x0 from above, settled, then the pass to x1 at its speed pressing `press` in, held at its end") {
    drivers::FingerSweep s;
    s.x0 = 0.17;
    s.x1 = -0.17;  // right to left
    s.speed = 0.1;
    s.press = 0.003;
    s.height = 0.02;
    const double before = drivers::kSweepDescent + drivers::kSweepSettle;  // s
    CHECK(drivers::finger_sweep_duration(s) == doctest::Approx(3.4));
    const Vec2 above = drivers::finger_sweep_at(s, 0.0), halfway_down = drivers::finger_sweep_at(s, 0.5 * drivers::kSweepDescent);
    const Vec2 start = drivers::finger_sweep_at(s, before), mid = drivers::finger_sweep_at(s, before + 1.7),
               end = drivers::finger_sweep_at(s, 99.0);
    // 15 mm above the pressed height first: out of contact (R - press + 15 mm over the floor).
    CHECK(above.x == 0.17);
    CHECK(above.y == doctest::Approx(s.finger_radius - s.press + 0.015).epsilon(1e-12));
    CHECK(halfway_down.y == doctest::Approx(s.finger_radius - s.press + 0.0075).epsilon(1e-12));
    CHECK(start.x == 0.17);
    CHECK(start.y == doctest::Approx(s.finger_radius - s.press).epsilon(1e-12));
    CHECK(drivers::finger_sweep_at(s, before - 0.01).x == 0.17);  // settled, not yet moving
    CHECK(end.x == -0.17);
    CHECK(mid.x == doctest::Approx(0.0).scale(1.0).epsilon(1e-12));
    CHECK(mid.y == doctest::Approx(s.height + s.finger_radius - s.press).epsilon(1e-12));
}

TEST_CASE("live session: seed 003's trial sweeps the arc of the trial's height, left to right for A and right to left for B") {
    TempDir dir;
    experiments::LiveSession session(experiments::load_protocol((cli_test::source_dir() / "scenes/experiments/003-curvature.json").string()),
                                     "P1", 1, dir.file("p1.csv"));
    int a = 0, b = 0;
    while (!session.finished()) {
        const auto sweep = session.sweep();
        REQUIRE(sweep);
        const bool motion_a = session.condition().motion == "A";
        CHECK(sweep->height == session.trial().stimulus);
        CHECK(sweep->chord == session.protocol().chord);
        CHECK(sweep->speed == session.protocol().hand_speed);
        CHECK(sweep->finger_radius == session.protocol().finger_radius);
        // From 2 cm before the arc to 2 cm after it, the way the condition says.
        CHECK(sweep->x0 == doctest::Approx(motion_a ? -0.17 : 0.17));
        CHECK(sweep->x1 == doctest::Approx(-sweep->x0));
        (motion_a ? a : b) += 1;
        experiments::LiveTrialResult r;
        r.response = "20";
        r.touched = true;
        session.answer(r);
    }
    CHECK(a == 12);
    CHECK(b == 12);
    CHECK_FALSE(session.sweep());  // finished: nothing to play
}
