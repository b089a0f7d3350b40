// scene.cpp — endpoint, tangent and length of scene segments.
#include "haptics/scene.hpp"

namespace contactlab {
namespace {
// +1 for a counter-clockwise arc, -1 for a clockwise one.
double arc_direction(const ArcSegment& a) { return a.end_angle >= a.start_angle ? 1.0 : -1.0; }
}  // namespace

Vec2 segment_start(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return l->from;
    const auto& a = std::get<ArcSegment>(s);
    return a.center + a.radius * unit_at(a.start_angle);
}

Vec2 segment_end(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return l->to;
    const auto& a = std::get<ArcSegment>(s);
    return a.center + a.radius * unit_at(a.end_angle);
}

Vec2 segment_start_tangent(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return glm::normalize(l->to - l->from);
    const auto& a = std::get<ArcSegment>(s);
    return arc_direction(a) * perp_left(unit_at(a.start_angle));
}

Vec2 segment_end_tangent(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return glm::normalize(l->to - l->from);
    const auto& a = std::get<ArcSegment>(s);
    return arc_direction(a) * perp_left(unit_at(a.end_angle));
}

double segment_length(const Segment& s) {
    if (auto* l = std::get_if<LineSegment>(&s)) return glm::length(l->to - l->from);
    const auto& a = std::get<ArcSegment>(s);
    return a.radius * std::abs(a.end_angle - a.start_angle);
}

}  // namespace contactlab
