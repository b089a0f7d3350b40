// stimulus.cpp — scenes and hand paths for each task (stimulus.hpp).
#include "engine/experiments/protocol/stimulus.hpp"

#include "engine/experiments/protocol/surface_profile.hpp"
#include "engine/experiments/base/trial_profile.hpp"
#include "engine/experiments/base/random_stream.hpp"

#include "drivers/tasks.hpp"
#include "haptics/bezier.hpp"
#include "haptics/force_law.hpp"
#include "haptics/stimuli.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

namespace contactlab::experiments {
namespace {

constexpr double kSample = 1e-3;  // s between hand path samples

constexpr double kPointStep = 2.5e-4;  // m between surface points, at most

}  // namespace

// How many intervals surface_points cuts a segment into: ceil(length / kPointStep), at least 2,
// with segment_length's length. For a quadratic curve that length is a quadrature of 320 square
// roots (a tenth of a seed 002 hand path's time), while the count needs only which multiple of
// kPointStep the length lies below: the curve's length lies between its chord and its control
// polygon, and between the chords and the control polygons of its halves, quarters, ... (de
// Casteljau). When every length in that interval, widened by 1e-6 of itself (the quadrature is
// exact to ~1e-14 for a curve whose direction never reverses, and the roundings of the bounds to
// ~1e-16), gives the same count, that is the count; otherwise (a length within a micrometre of a
// multiple, or a curve that turns back on itself) the quadrature decides, as before.
int surface_intervals(const Segment& seg) {
    auto count = [](double length) { return std::max(2, static_cast<int>(std::ceil(length / kPointStep))); };
    const auto* q = std::get_if<QuadSegment>(&seg);
    if (q == nullptr || !(glm::dot(q->p1 - q->p0, q->p2 - q->p1) > 0.0)) return count(segment_length(seg));
    struct Piece {
        Vec2 a, b, c;
    };
    Piece pieces[16] = {{q->p0, q->p1, q->p2}};
    int n = 1;
    for (;;) {
        double lo = 0.0, hi = 0.0;  // m: the chords' and the control polygons' lengths
        for (int i = 0; i < n; ++i) {
            lo += glm::length(pieces[i].c - pieces[i].a);
            hi += glm::length(pieces[i].b - pieces[i].a) + glm::length(pieces[i].c - pieces[i].b);
        }
        const int fewest = count(lo * (1.0 - 1e-6)), most = count(hi * (1.0 + 1e-6));
        if (fewest == most) return fewest;
        if (2 * n > 16) return count(segment_length(seg));
        for (int i = n - 1; i >= 0; --i) {  // each piece into its halves
            const Piece p = pieces[i];
            const Vec2 ab = 0.5 * (p.a + p.b), bc = 0.5 * (p.b + p.c), mid = 0.5 * (ab + bc);
            pieces[2 * i] = {p.a, ab, mid};
            pieces[2 * i + 1] = {mid, bc, p.c};
        }
        n *= 2;
    }
}

namespace {

// Points along every segment of the scene, about every 0.25 mm.
std::vector<Vec2> surface_points(const Scene& s) {
    std::vector<Vec2> out;
    for (const Contour& c : s.contours)
        for (const Segment& seg : c.segments) {
            const int n = surface_intervals(seg);
            for (int i = 0; i <= n; ++i) {
                const double u = static_cast<double>(i) / n;
                if (const auto* l = std::get_if<LineSegment>(&seg)) {
                    out.push_back(l->from + (l->to - l->from) * u);
                } else if (const auto* a = std::get_if<ArcSegment>(&seg)) {
                    const double ang = a->start_angle + (a->end_angle - a->start_angle) * u;
                    out.push_back(a->center + a->radius * Vec2{std::cos(ang), std::sin(ang)});
                } else {
                    out.push_back(bezier_point(segment_bezier(seg), u));
                }
            }
        }
    return out;
}

// Descend onto x0, settle, slide to x1 at `speed` (along x) keeping `press` below the resting
// height, hold. The finger turns with the surface's slope over +-15 mm (a person keeps the pad on
// the contour, seed 002's gimbal measures it): the pad reaches slopes only within L / 2R of its
// axis, and seed 002's base shape is steeper than that.
drivers::HandPath slide_path(const SurfaceProfile& pts, double x0, double x1, double r, double speed, double press,
                             double& slide_start, double& slide_end, PathUse use) {
    RestingCursor at, ahead, behind;  // where each of the three heights was last found
    auto height = [&](double x, RestingCursor& cursor) { return resting_height(pts, x, r, cursor) - press; };
    // The slide's positions and heights first: a slope asks for the heights 15 mm either side of
    // a position, and about half of those positions are, to the last bit, slide positions 300
    // samples away, whose heights are then taken from here (a height is a function of x alone).
    const int n = static_cast<int>(std::ceil(std::abs(x1 - x0) / (speed * kSample)));
    std::vector<double> xs(static_cast<std::size_t>(n) + 1), hs(xs.size());
    for (int i = 0; i <= n; ++i) {
        xs[static_cast<std::size_t>(i)] = x0 + (x1 - x0) * i / n;
        hs[static_cast<std::size_t>(i)] = height(xs[static_cast<std::size_t>(i)], at);
    }
    constexpr double h = 0.015;  // m
    const double step = (x1 - x0) / n;  // m a sample (signed)
    const long span = std::isfinite(h / step) ? std::lround(h / step) : 0;  // samples 15 mm on (signed)
    // The height at x, which lies about `offset` samples from sample i.
    auto height_near = [&](double x, long i, long offset, RestingCursor& cursor) {
        for (const long j : {i + offset, i + offset - 1, i + offset + 1})
            if (j >= 0 && j <= n && xs[static_cast<std::size_t>(j)] == x) return hs[static_cast<std::size_t>(j)];
        return height(x, cursor);
    };
    // The finger turns with the surface's slope over +-15 mm.
    auto slope = [&](long i) {
        const double x = xs[static_cast<std::size_t>(i)];
        return std::clamp(std::atan2(height_near(x + h, i, span, ahead) - height_near(x - h, i, -span, behind), 2.0 * h), -1.4,
                          1.4);  // rad
    };
    std::vector<drivers::PathSample> out;
    out.reserve(xs.size() + 800);
    double t = 0.0;
    const double y0 = hs[0], phi0 = slope(0);  // xs[0] is x0
    const Vec2 above{x0, y0 + 0.015};
    auto push = [&](Vec2 x, double phi) {
        out.push_back({t, x, phi});
        t += kSample;
    };
    for (int i = 0; i < 300; ++i) push(above + (Vec2{x0, y0} - above) * (i / 300.0), phi0);  // 0.3 s down
    for (int i = 0; i < 300; ++i) push({x0, y0}, phi0);                                      // 0.3 s settle
    slide_start = t;
    for (int i = 0; i <= n; ++i)
        push({xs[static_cast<std::size_t>(i)], hs[static_cast<std::size_t>(i)]}, i == 0 || use == PathUse::envelope ? phi0 : slope(i));
    slide_end = t;
    const drivers::PathSample last = out.back();
    for (int i = 0; i < 200; ++i) push(last.x, last.phi);  // 0.2 s hold
    return drivers::HandPath(std::move(out));
}

// What the protocol sets of how a stimulus is rendered: the pad, the force, and the curves' mode.
void set_rendering(Scene& s, const Protocol& p) {
    s.curves = p.curves;  // exact unless the protocol asks for flattened curves
    s.finger.radius = p.finger_radius;
    s.finger.length = p.pad_length;
    s.force.stiffness = p.stiffness;
    s.force.max_force = p.max_force;
}

}  // namespace

Scene generate_edge(double radius, double slope, double half_width) {
    // The faces meet at the apex (0, 0); the arc's centre lies below it at radius / cos(slope),
    // where it is `radius` from both faces, and the arc runs clockwise over the top (convex).
    const Vec2 center{0.0, -radius / std::cos(slope)};
    const double a0 = 0.5 * kPi + slope, a1 = 0.5 * kPi - slope;
    const Vec2 left = center + radius * Vec2{std::cos(a0), std::sin(a0)}, right = center + radius * Vec2{std::cos(a1), std::sin(a1)};
    Scene s;
    Contour c;
    c.segments.push_back(LineSegment{{-half_width, -half_width * std::tan(slope)}, left});
    c.segments.push_back(ArcSegment{center, radius, a0, a1});
    c.segments.push_back(LineSegment{right, {half_width, -half_width * std::tan(slope)}});
    s.contours.push_back(c);
    return s;
}

Stimulus make_edge_stimulus(const Protocol& p, double radius) {
    const StageTimer timer(&TrialProfile::stimulus);
    Stimulus st;
    st.scene = generate_edge(radius, p.edge_slope_deg * kPi / 180.0, 0.05);
    set_rendering(st.scene, p);
    const SurfaceProfile pts = profile_of(surface_points(st.scene));
    st.path = slide_path(pts, -0.03, 0.03, p.finger_radius, p.hand_speed, p.hand_press, st.slide_start, st.slide_end, PathUse::script);
    return st;
}

double edge_radius(const Protocol& p, const PlannedTrial& t, int interval) {
    return p.reference_radius + (interval == comparison_interval(t.seed) ? t.stimulus * 1e-3 : 0.0);
}

double curvature_slide_start(const Protocol& p, const Condition& c) {
    const double half = 0.5 * p.chord + 0.02;  // m: from before the arc to after it
    return c.motion == "B" ? half : -half;
}

double arc_slope_range_deg(double chord, double height) {
    const double ra = arc_cap_radius(chord, height);
    return 2.0 * std::asin(std::min(1.0, chord / (2.0 * ra))) * 180.0 / kPi;
}

Stimulus make_stimulus(const Protocol& p, const Condition& c, const PlannedTrial& t, double overshoot, double top_speed,
                       PathUse use) {
    const StageTimer timer(&TrialProfile::stimulus);
    Stimulus st;
    std::uint64_t rng = t.seed;
    switch (p.task) {
        case Task::contour_following: {
            st.scene = generate_block(t.stimulus);
            set_rendering(st.scene, p);
            drivers::BlockTaskParams bp;
            bp.finger_radius = p.finger_radius;
            bp.d = t.stimulus;
            bp.speed = top_speed > 0.0 ? top_speed : p.hand_speed;
            bp.descent_speed = p.hand_speed;
            bp.press = p.hand_press;
            bp.overshoot = overshoot;
            bp.descent = p.finish_depth + 0.01;  // a centimetre past the finish line
            st.path = drivers::contour_block_task(bp);
            break;
        }
        case Task::bump_counting: {
            BumpsDef def;
            def.seed = mix64(rng);
            const int k = static_cast<int>(t.stimulus);
            for (int i = 0; i < k; ++i) (uniform01(rng) < 0.5 ? st.small_bumps : st.large_bumps) += 1;
            def.small_bumps = st.small_bumps;
            def.large_bumps = st.large_bumps;
            def.small_height = p.small_bump;
            def.large_height = p.large_bump;
            def.length = p.traced_length;
            def.base_span = p.base_span;
            st.scene = generate_bumps(def).scene;
            set_rendering(st.scene, p);
            const SurfaceProfile pts = profile_of(surface_points(st.scene));
            st.path = slide_path(pts, 0.01, p.traced_length - 0.01, p.finger_radius, p.hand_speed, p.hand_press,
                                 st.slide_start, st.slide_end, use);
            break;
        }
        case Task::curvature: {
            st.scene = generate_arc(p.chord, t.stimulus);
            set_rendering(st.scene, p);
            const SurfaceProfile pts = profile_of(surface_points(st.scene));
            const double x0 = curvature_slide_start(p, c);
            st.path = slide_path(pts, x0, -x0, p.finger_radius, p.hand_speed, p.hand_press, st.slide_start, st.slide_end, use);
            break;
        }
        case Task::surface_orientation: {
            Scene s;
            Contour floor;
            floor.segments.push_back(LineSegment{{-0.05, 0.0}, {0.05, 0.0}});
            s.contours.push_back(floor);
            set_rendering(s, p);
            ForceLaw& law = s.force.law;
            law.model = ForceModel::ellipsoid;
            law.k_tangential = tangential_stiffness_from(c.total_stiffness, c.eccentricity);
            law.k_normal = c.eccentricity * law.k_tangential;
            law.field_angle = (t.stimulus - 90.0) * kPi / 180.0;  // alpha = 90 deg + field_angle
            law.mu_static = law.mu_dynamic = 1.0;  // the stiction point holds while the finger probes
            s.force.stiffness = law.k_normal;
            st.scene = s;
            // Press 1 mm in, then 1 mm along each downward diagonal and back.
            const double r = p.finger_radius, depth = 0.001, probe = 0.001;
            const Vec2 above{0.0, r + 0.01}, in{0.0, r - depth};
            const Vec2 dl = in + probe * Vec2{-1.0, -1.0} / std::sqrt(2.0), dr = in + probe * Vec2{1.0, -1.0} / std::sqrt(2.0);
            std::vector<drivers::PathSample> out;
            double time = 0.0;
            auto move = [&](Vec2 a, Vec2 b, double seconds) {
                const int n = static_cast<int>(std::lround(seconds / kSample));
                for (int i = 0; i < n; ++i) {
                    out.push_back({time, a + (b - a) * (static_cast<double>(i) / n), 0.0});
                    time += kSample;
                }
            };
            move(above, in, 0.4);
            move(in, in, 0.4);
            st.probe[0] = time;
            move(in, dl, 0.3);
            move(dl, dl, 0.1);
            st.probe[1] = time;
            move(dl, in, 0.3);
            move(in, in, 0.2);
            st.probe[2] = time;
            move(in, dr, 0.3);
            move(dr, dr, 0.1);
            st.probe[3] = time;
            move(dr, in, 0.3);
            move(in, above, 0.3);
            out.push_back({time, above, 0.0});
            st.path = drivers::HandPath(std::move(out));
            break;
        }
        case Task::edge_sharpness: st = make_edge_stimulus(p, edge_radius(p, t, 1)); break;
    }
    return st;
}

}  // namespace contactlab::experiments
