// cost_scenes.cpp — profiles, their segmentations and the 1 mm deep strokes (cost_scenes.hpp).
#include "engine/bench/cost_scenes.hpp"

#include <cmath>
#include <numbers>

namespace contactlab::bench {
namespace {

constexpr double kPiece = 0.005;        // m, extent: width of one piece
constexpr double kDenseLength = 0.4;    // m, dense: the contour's length
constexpr double kPress = 0.001;        // m, depth of the stroke
constexpr double kPadRadius = 0.026;    // m, the default finger's R

struct Profile {
    Growth growth;
    double h(double x) const {
        if (growth == Growth::extent) return 0.005 * std::sin(60.0 * x) + 0.003 * std::sin(170.0 * x + 1.0);
        return 0.01 * std::sin(2.0 * std::numbers::pi * x / 0.1);
    }
    double slope(double x) const {
        if (growth == Growth::extent) return 0.3 * std::cos(60.0 * x) + 0.51 * std::cos(170.0 * x + 1.0);
        return 0.01 * 2.0 * std::numbers::pi / 0.1 * std::cos(2.0 * std::numbers::pi * x / 0.1);
    }
    Vec2 at(double x) const { return {x, h(x)}; }
};

// A circle through a, m, b travelled from a to b through m, or a line when they are (nearly)
// collinear. Solid below: the profile is travelled left to right, solid on the right.
Segment arc_through(Vec2 a, Vec2 m, Vec2 b) {
    const double d = 2.0 * (a.x * (m.y - b.y) + m.x * (b.y - a.y) + b.x * (a.y - m.y));
    const double scale = glm::length(b - a);
    if (std::abs(d) <= 1e-9 * scale * scale) return LineSegment{a, b};
    const double a2 = glm::dot(a, a), m2 = glm::dot(m, m), b2 = glm::dot(b, b);
    const Vec2 c{(a2 * (m.y - b.y) + m2 * (b.y - a.y) + b2 * (a.y - m.y)) / d,
                 (a2 * (b.x - m.x) + m2 * (a.x - b.x) + b2 * (m.x - a.x)) / d};
    const double r = glm::length(a - c);
    if (r > 1e3) return LineSegment{a, b};
    const double two_pi = 2.0 * std::numbers::pi;
    auto wrap = [&](double v) { v = std::fmod(v, two_pi); return v < 0.0 ? v + two_pi : v; };
    const double a0 = std::atan2(a.y - c.y, a.x - c.x);
    const double ccw = wrap(std::atan2(b.y - c.y, b.x - c.x) - a0);
    const bool through_m_ccw = wrap(std::atan2(m.y - c.y, m.x - c.x) - a0) < ccw;
    const double a1 = through_m_ccw ? a0 + ccw : a0 - (two_pi - ccw);
    ArcSegment arc{c, r, a0, a1};
    return arc;
}

}  // namespace

std::string case_key(SegmentKind kind, Growth growth) {
    const char* k = kind == SegmentKind::lines ? "lines" : kind == SegmentKind::arcs ? "arcs" : "curves";
    return std::string(k) + (growth == Growth::dense ? "_dense" : "");
}

Scene cost_scene(const CostCase& c) {
    const Profile p{c.growth};
    const double width = c.growth == Growth::extent ? kPiece : kDenseLength / c.segments;
    Scene scene;
    Contour contour;
    contour.segments.reserve(static_cast<std::size_t>(c.segments));
    // Arc ends are recomputed from the circle, so chain each piece from where the last one ended.
    Vec2 from = p.at(0.0);
    for (int i = 0; i < c.segments; ++i) {
        const double x0 = i * width, x1 = (i + 1) * width, xm = 0.5 * (x0 + x1);
        const Vec2 to = p.at(x1);
        switch (c.kind) {
            case SegmentKind::lines: contour.segments.push_back(LineSegment{from, to}); break;
            case SegmentKind::arcs: {
                const Segment s = arc_through(from, p.at(xm), to);
                contour.segments.push_back(s);
                // Far from the origin the circle's end misses `to` by rounding: the next piece
                // starts where this one really ends, so joins stay exact.
                if (const auto* arc = std::get_if<ArcSegment>(&s))
                    from = arc->center + arc->radius * Vec2{std::cos(arc->end_angle), std::sin(arc->end_angle)};
                else
                    from = to;
                continue;
            }
            case SegmentKind::curves: {
                // Passing the profile's midpoint at t = 1/2: p1 = 2 m - (p0 + p2) / 2.
                const Vec2 mid = p.at(xm);
                contour.segments.push_back(QuadSegment{from, 2.0 * mid - 0.5 * (from + to), to});
                break;
            }
        }
        from = to;
    }
    scene.contours.push_back(std::move(contour));
    return scene;
}

std::vector<FingerSample> cost_stroke(const CostCase& c, int ticks) {
    const Profile p{c.growth};
    double start = 0.0, span = 0.0;
    if (c.growth == Growth::extent) {
        const double length = c.segments * kPiece;
        span = std::min(2.0, 0.4 * length);
        start = 0.5 * (length - span);
    } else {
        span = 0.2;
        start = 0.5 * (kDenseLength - span);
    }
    std::vector<FingerSample> path;
    path.reserve(static_cast<std::size_t>(ticks));
    for (int k = 0; k < ticks; ++k) {
        const double x = start + span * k / ticks;
        const Vec2 n = glm::normalize(Vec2{-p.slope(x), 1.0});
        path.push_back({1e-3 * k, p.at(x) + (kPadRadius - kPress) * n, 0.0});
    }
    return path;
}

}  // namespace contactlab::bench
