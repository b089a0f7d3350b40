// frame_finger.cpp — the finger (body outline, pad highlighted), the proxy as a ghost finger, the
// contacts, the force arrow, the target contact location on the pad and the anticipation marker.
//
// Finger frame: axis a = (cos phi, sin phi) points to the fingertip, up = a rotated +90 deg. The
// body is the pad circle's arc from the pad's proximal end, round the tip, to the top, then a
// straight body 2.5 R long back toward the hand.
#include "engine/render/frame_parts.hpp"

#include "engine/render/text.hpp"
#include "haptics/finger.hpp"

#include <cmath>
#include <cstdio>
#include <tuple>

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

    // Seed 003's platform under the pad (side view): Table 2's B_i lie 4 mm behind and 8 mm ahead of
    // its centre along the finger, the A_i on the nail side 11 mm behind and 15 mm ahead of the
    // pad's middle; the cables run B -> A round the finger (drawn straight across it), each
    // pulling with an arrow of its tension.
    if (c.platform) {
        const PlatformDrawing& pd = *c.platform;
        const Vec2 t = unit_at(o.phi);
        const Vec2 p0 = pad_point(o.finger, o.phi, c.shape, 0.0);
        const Vec2 n_in = (o.finger - p0) / c.shape.radius;  // from the pad into the finger
        const Vec2 centre = p0 + pd.press * n_in;
        const Vec2 dir = std::cos(pd.roll) * t + std::sin(pd.roll) * n_in;
        const Vec2 b_prox = centre - 0.004 * dir, b_dist = centre + 0.008 * dir;
        const Vec2 top = o.finger + c.shape.radius * n_in;
        const Vec2 a_prox = top - 0.011 * t, a_dist = top + 0.015 * t;
        const Color cable = theme.cable.with_alpha(170);
        out.line(view.to_px(b_prox), view.to_px(a_prox), m.outline_width * 0.75f, cable);
        out.line(view.to_px(b_dist), view.to_px(a_dist), m.outline_width * 0.75f, cable);
        out.line(view.to_px(centre - 0.006 * dir), view.to_px(centre + 0.008 * dir), m.pad_width * 1.5f, theme.target);
        const double prox = pd.tension[0] + pd.tension[1], dist = pd.tension[2];  // N
        for (const auto& [b, a, q] : {std::tuple{b_prox, a_prox, prox}, std::tuple{b_dist, a_dist, dist}}) {
            if (!(q > 0.0) || !(pd.full_tension > 0.0)) continue;
            const P2 from = view.to_px(b), to_a = view.to_px(a);
            const P2 d = to_a - from;
            const float dl = glm::length(d);
            if (dl < 0.5f) continue;
            const float len = static_cast<float>(std::min(q / pd.full_tension, 1.0)) * m.arrow_full;
            arrow(from, from + d / dl * len, m.arrow_width * 0.75f, theme.cable, out);
            if (c.text) {
                char label[32];
                std::snprintf(label, sizeof label, "%.2f N", q);
                draw_text(out, from + d / dl * len + P2(4.0f, 0.0f), label, theme.cable, m.text_scale);
            }
        }
        // The contact frame at the platform's centre: t along the platform (toward the
        // fingertip), n into the finger; labelled with the text.
        const float axis = 0.35f * m.arrow_full;
        const P2 o_px = view.to_px(centre);
        const P2 t_px = view.to_px(centre + dir) - o_px, n_px = view.to_px(centre + (-std::sin(pd.roll) * t + std::cos(pd.roll) * n_in)) - o_px;
        const P2 t_end = o_px + t_px / glm::length(t_px) * axis, n_end = o_px + n_px / glm::length(n_px) * axis;
        arrow(o_px, t_end, m.outline_width, theme.legend, out);
        arrow(o_px, n_end, m.outline_width, theme.legend, out);
        if (c.text) {
            draw_text(out, t_end + P2(3.0f, 3.0f), "t", theme.legend, m.text_scale);
            draw_text(out, n_end + P2(3.0f, -3.0f), "n", theme.legend, m.text_scale);
            // Under the origin, on the side away from the finger (n points into it).
            const P2 size = text_size("contact frame", m.text_scale);
            const P2 away = -n_px / glm::length(n_px);
            const P2 at = o_px + away * (2.5f * m.dot_radius + 0.5f * size.y) - 0.5f * size;
            draw_text(out, at, "contact frame", theme.legend, m.text_scale);
        }
    }

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
