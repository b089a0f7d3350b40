// scene.cpp — endpoint, tangent and length of scene segments.
#include "haptics/scene.hpp"

#include "haptics/bezier.hpp"

namespace contactlab {

const char* curve_mode_name(CurveMode mode) { return mode == CurveMode::exact ? "exact" : "flatten"; }

std::optional<CurveMode> curve_mode_named(std::string_view name) {
    if (name == "exact") return CurveMode::exact;
    if (name == "flatten") return CurveMode::flatten;
    return std::nullopt;
}

namespace {
// +1 for a counter-clockwise arc, -1 for a clockwise one.
double arc_direction(const ArcSegment& a) { return a.end_angle >= a.start_angle ? 1.0 : -1.0; }

Bezier bezier_of(const QuadSegment& q) { return {2, {q.p0, q.p1, q.p2, Vec2{0.0}}}; }
Bezier bezier_of(const CubicSegment& c) { return {3, {c.p0, c.p1, c.p2, c.p3}}; }

// Unit tangent of a curve at s in {0, 1}: the derivative, or where it vanishes (coincident
// control points) the direction toward the next distinct control point.
Vec2 curve_end_tangent(const Bezier& b, bool at_end) {
    const Vec2 d = bezier_derivative(b, at_end ? 1.0 : 0.0);
    if (glm::length(d) > 0.0) return glm::normalize(d);
    const Vec2 d2 = bezier_derivative(b, at_end ? 1.0 - 1e-7 : 1e-7);
    return glm::length(d2) > 0.0 ? glm::normalize(d2) : Vec2{1.0, 0.0};
}
}  // namespace

bool segment_is_curve(const Segment& s) {
    return std::holds_alternative<QuadSegment>(s) || std::holds_alternative<CubicSegment>(s);
}

Vec2 segment_start(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return l->from;
    if (auto* q = std::get_if<QuadSegment>(&s)) return q->p0;
    if (auto* c = std::get_if<CubicSegment>(&s)) return c->p0;
    const auto& a = std::get<ArcSegment>(s);
    return a.center + a.radius * unit_at(a.start_angle);
}

Vec2 segment_end(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return l->to;
    if (auto* q = std::get_if<QuadSegment>(&s)) return q->p2;
    if (auto* c = std::get_if<CubicSegment>(&s)) return c->p3;
    const auto& a = std::get<ArcSegment>(s);
    return a.center + a.radius * unit_at(a.end_angle);
}

Vec2 segment_start_tangent(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return glm::normalize(l->to - l->from);
    if (auto* q = std::get_if<QuadSegment>(&s)) return curve_end_tangent(bezier_of(*q), false);
    if (auto* c = std::get_if<CubicSegment>(&s)) return curve_end_tangent(bezier_of(*c), false);
    const auto& a = std::get<ArcSegment>(s);
    return arc_direction(a) * perp_left(unit_at(a.start_angle));
}

Vec2 segment_end_tangent(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return glm::normalize(l->to - l->from);
    if (auto* q = std::get_if<QuadSegment>(&s)) return curve_end_tangent(bezier_of(*q), true);
    if (auto* c = std::get_if<CubicSegment>(&s)) return curve_end_tangent(bezier_of(*c), true);
    const auto& a = std::get<ArcSegment>(s);
    return arc_direction(a) * perp_left(unit_at(a.end_angle));
}

double segment_length(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return glm::length(l->to - l->from);
    if (segment_is_curve(s)) {
        // Arc length by 5-point Gauss-Legendre on 64 sub-intervals (exact to ~1e-12 relative for
        // any curve a scene holds; used for validation and display, not in the servo).
        const Bezier b = std::holds_alternative<QuadSegment>(s) ? bezier_of(std::get<QuadSegment>(s))
                                                                : bezier_of(std::get<CubicSegment>(s));
        static constexpr double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                        0.9061798459386640};
        static constexpr double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                        0.2369268850561891, 0.2369268850561891};
        double total = 0.0;
        constexpr int kParts = 64;
        for (int i = 0; i < kParts; ++i) {
            const double a = static_cast<double>(i) / kParts, h = 1.0 / kParts;
            for (int k = 0; k < 5; ++k) total += 0.5 * h * w[k] * glm::length(bezier_derivative(b, a + 0.5 * h * (x[k] + 1.0)));
        }
        return total;
    }
    const auto& a = std::get<ArcSegment>(s);
    return a.radius * std::abs(a.end_angle - a.start_angle);
}

Bezier segment_bezier(const Segment& s) {
    if (auto* q = std::get_if<QuadSegment>(&s)) return bezier_of(*q);
    return bezier_of(std::get<CubicSegment>(s));
}

void set_force_model(ForceDef& force, ForceModel model) {
    if (force.law.model == model) return;
    ForceLaw& law = force.law;
    if (model == ForceModel::ellipsoid) {
        const bool has_e = law.k_tangential > 0.0 && law.k_normal > 0.0 && std::isfinite(law.k_normal / law.k_tangential);
        const double e = has_e ? law.k_normal / law.k_tangential : 1.0;
        law.k_normal = force.stiffness;
        law.k_tangential = force.stiffness / e;
    } else {
        force.stiffness = law.k_normal;
    }
    law.model = model;
}

}  // namespace contactlab
