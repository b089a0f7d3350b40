// frame_finger.cpp — the finger (body outline, pad highlighted), the proxy as a ghost finger, the
// contacts, the force arrow, the target contact location on the pad and the anticipation marker.
//
// Finger frame: axis a = (cos phi, sin phi) points to the fingertip, up = a rotated +90 deg. The
// body is the pad circle's arc from the pad's proximal end, round the tip, to the top, then a
// straight body 2.5 R long back toward the hand.
#include "engine/render/frame_parts.hpp"

#include "haptics/finger.hpp"

#include <cmath>

namespace contactlab::render::parts {
namespace {

constexpr double kBodyLength = 2.5;  // in R, behind the pad circle's centre

// World points of a circular arc, flattened for the view.
void world_arc(Vec2 c, double r, double a0, double a1, const View& view, std::vector<P2>& out) {
    const int n = arc_chord_count(r * view.px_per_m, a1 - a0, kFlattenTolerancePx);
    for (int i = 0; i <= n; ++i) out.push_back(view.to_px(c + r * unit_at(a0 + (a1 - a0) * i / n)));
}

// Pad point at contact location l (m) for a finger at c with angle phi.
Vec2 pad_point(Vec2 c, double phi, const FingerShape& shape, double l) {
    return c + shape.radius * unit_at(pad_mid_angle(phi) + l / shape.radius);
}

void arrow(P2 from, P2 to, float width, Color color, DrawList& out) {
    const P2 d = to - from;
    const float len = glm::length(d);
    if (len < 0.5f) return;
    const P2 u = d / len, n(-u.y, u.x);
    const float head = std::min(len, width * 4.0f);
    out.line(from, to - u * (head * 0.8f), width, color);
    const P2 tri[3] = {to, to - u * head + n * (head * 0.45f), to - u * head - n * (head * 0.45f)};
    out.fill_convex(tri, color);
}

}  // namespace

void draw_finger_body(Vec2 center, double phi, const FingerShape& shape, const View& view, Color fill, Color outline,
                      Color pad, const Metrics& m, DrawList& out) {
    const double R = shape.radius, h = pad_half_angle(shape);
    const Vec2 a = unit_at(phi), up = unit_at(phi + 0.5 * kPi);
    std::vector<P2> body;
    world_arc(center, R, pad_mid_angle(phi) - h, phi + 0.5 * kPi, view, body);
    body.push_back(view.to_px(center + R * up - kBodyLength * R * a));
    body.push_back(view.to_px(center - R * std::cos(h) * up - kBodyLength * R * a));
    if (fill.a) out.fill_polygon(body, fill);
    out.stroke(body, true, m.outline_width, outline);
    std::vector<P2> pad_arc;
    world_arc(center, R, pad_mid_angle(phi) - h, pad_mid_angle(phi) + h, view, pad_arc);
    out.stroke(pad_arc, false, m.pad_width, pad);
}

void draw_proxy_state(const FrameContent& c, const View& view, const Theme& theme, const Metrics& m, DrawList& out) {
    const ProxyOutput& o = *c.finger;
    // Ghost finger at the proxy (only when it differs from the finger: in contact).
    if (o.contact)
        draw_finger_body(o.proxy, o.phi, c.shape, view, Color{}.with_alpha(0), theme.proxy, theme.proxy.with_alpha(110),
                         m, out);
    // The finger as measured.
    draw_finger_body(o.finger, o.phi, c.shape, view, theme.finger_fill, theme.finger_outline, theme.pad, m, out);

    // Target contact location l_d on the finger's pad: a ring (where the roller is driven).
    const P2 target = view.to_px(pad_point(o.finger, o.phi, c.shape, o.l_d));
    if (o.contact || o.anticipating) out.stroke_circle(target, m.dot_radius * 1.4f, m.outline_width, theme.target);
    // The roller where the device says it is: a filled dot on the pad.
    if (c.roller_l) out.fill_disc(view.to_px(pad_point(o.finger, o.phi, c.shape, *c.roller_l)), m.dot_radius * 0.8f, theme.target);

    // Force on the finger, from the target site, full length at max force.
    const double f = glm::length(o.force);
    if (o.contact && f > 0.0 && c.max_force > 0.0) {
        const Vec2 dir = o.force / f;
        const float len = static_cast<float>(std::min(f / c.max_force, 1.0)) * m.arrow_full;
        const P2 to = target + P2(static_cast<float>(dir.x), static_cast<float>(-dir.y)) * len;
        arrow(target, to, m.arrow_width, theme.force, out);
    }

    // Contacts on the contour, over the arrow.
    for (int i = 0; i < o.contact_count && i < static_cast<int>(o.contacts.size()); ++i)
        out.fill_disc(view.to_px(o.contacts[i].point), m.dot_radius, theme.contact);

    // Anticipation (free space): the expected contact on the contour, joined to the pad target.
    if (!o.contact && o.anticipating) {
        const P2 p = view.to_px(o.anticipated_point);
        out.line(target, p, m.outline_width * 0.75f, theme.anticipation.with_alpha(120));
        out.stroke_circle(p, m.dot_radius, m.outline_width, theme.anticipation);
    }
}

}  // namespace contactlab::render::parts
