// frame_finger.cpp — the finger (body outline, pad highlighted), the proxy as a ghost finger, the
// contacts, the force arrow, the target contact location on the pad and the anticipation marker.
//
// Finger frame: axis a = (cos phi, sin phi) points to the fingertip, up = a rotated +90 deg. The
// body is the pad circle's arc from the pad's proximal end, round the tip, to the top, then a
// straight body 2.5 R long back toward the hand.
#include "engine/render/frame_parts.hpp"

#include "engine/render/label_place.hpp"
#include "engine/render/text.hpp"
#include "haptics/finger.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

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

// The environment's pieces inside `region` (px) as strokes of the contour's width. Runs of
// pieces shorter than 1.5 px (a dense outline) are joined into one stroke per 1.5 px of path, so
// the count stays near the region's path length in px, not the contour's density.
void add_contour_marks(const Environment& env, const View& view, const LabelBox& region, float width, LabelMarks& marks) {
    const Vec2 w0 = view.to_world(region.lo.x, region.hi.y), w1 = view.to_world(region.hi.x, region.lo.y);
    Aabb box;
    box.grow(w0);
    box.grow(w1);
    std::vector<int> hits;
    env.tree.query(box, hits);
    std::sort(hits.begin(), hits.end());  // chain order within a contour
    std::vector<P2> pts;
    P2 run_start{0.0f}, run_end{0.0f};
    int last = -1;
    auto flush = [&] {
        if (last >= 0 && run_end != run_start) marks.add_stroke(run_start, run_end, width);
    };
    for (const int i : hits) {
        const EnvSegment& s = env.segments[i];
        pts.clear();
        if (s.kind == EnvSegment::Kind::line) {
            pts = {view.to_px(s.start), view.to_px(s.end)};
        } else {
            const int n = arc_chord_count(s.radius * view.px_per_m, s.angles.width, 0.5);
            for (int k = 0; k <= n; ++k) pts.push_back(view.to_px(s.center + s.radius * unit_at(s.angles.start + s.angles.width * k / n)));
        }
        const bool joined = last >= 0 && env.segments[last].next == i && glm::length(pts.front() - run_end) < 0.01f;
        if (!joined) {
            flush();
            run_start = run_end = pts.front();
        }
        for (std::size_t k = 1; k < pts.size(); ++k) {
            run_end = pts[k];
            if (glm::length(run_end - run_start) >= 1.5f) {
                marks.add_stroke(run_start, run_end, width);
                run_start = run_end;
            }
        }
        last = i;
    }
    flush();
}

void draw_finger_body(Vec2 center, double phi, const FingerShape& shape, const View& view, Color fill, Color outline,
                      Color pad, const Metrics& m, DrawList& out, LabelMarks* marks) {
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
    if (marks) {
        marks->add_polyline(body, true, m.outline_width);
        marks->add_polyline(pad_arc, false, m.pad_width);
    }
}

void draw_proxy_state(const FrameContent& c, const View& view, const Theme& theme, const Metrics& m, DrawList& out,
                      LabelMarks& marks) {
    const ProxyOutput& o = *c.finger;
    // Labels wait until every mark is drawn (label_place.hpp): placed in this order, each in the
    // first free place around its anchor, first toward `toward`.
    struct PendingLabel {
        std::string text;
        Color color;
        P2 anchor, toward;
        float gap;
    };
    std::vector<PendingLabel> labels;

    // Ghost finger at the proxy (only when it differs from the finger: in contact).
    if (o.contact)
        draw_finger_body(o.proxy, o.phi, c.shape, view, Color{}.with_alpha(0), theme.proxy, theme.proxy.with_alpha(110),
                         m, out, &marks);
    // The finger as measured.
    draw_finger_body(o.finger, o.phi, c.shape, view, theme.finger_fill, theme.finger_outline, theme.pad, m, out, &marks);

    // Target contact location l_d on the finger's pad: a ring (where the roller is driven).
    const P2 target = view.to_px(pad_point(o.finger, o.phi, c.shape, o.l_d));
    if (o.contact || o.anticipating) {
        out.stroke_circle(target, m.dot_radius * 1.4f, m.outline_width, theme.target);
        marks.add_disc(target, m.dot_radius * 1.4f + 0.5f * m.outline_width);
    }
    // The roller where the device says it is: a filled dot on the pad.
    if (c.roller_l) {
        const P2 roller = view.to_px(pad_point(o.finger, o.phi, c.shape, *c.roller_l));
        out.fill_disc(roller, m.dot_radius * 0.8f, theme.target);
        marks.add_disc(roller, m.dot_radius * 0.8f);
    }

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
        for (const auto& [b, a] : {std::pair{b_prox, a_prox}, std::pair{b_dist, a_dist}}) {
            out.line(view.to_px(b), view.to_px(a), m.outline_width * 0.75f, cable);
            marks.add_stroke(view.to_px(b), view.to_px(a), m.outline_width * 0.75f);
        }
        const P2 bar0 = view.to_px(centre - 0.006 * dir), bar1 = view.to_px(centre + 0.008 * dir);
        out.line(bar0, bar1, m.pad_width * 1.5f, theme.target);
        marks.add_stroke(bar0, bar1, m.pad_width * 1.5f);
        const double prox = pd.tension[0] + pd.tension[1], dist = pd.tension[2];  // N
        for (const auto& [b, a, q] : {std::tuple{b_prox, a_prox, prox}, std::tuple{b_dist, a_dist, dist}}) {
            if (!(q > 0.0) || !(pd.full_tension > 0.0)) continue;
            const P2 from = view.to_px(b), to_a = view.to_px(a);
            const P2 d = to_a - from;
            const float dl = glm::length(d);
            if (dl < 0.5f) continue;
            const float len = static_cast<float>(std::min(q / pd.full_tension, 1.0)) * m.arrow_full;
            const P2 tip = from + d / dl * len;
            arrow(from, tip, m.arrow_width * 0.75f, theme.cable, out);
            marks.add_stroke(from, tip, m.arrow_width * 0.75f * 4.0f * 0.9f);  // the head's width
            char label[32];
            std::snprintf(label, sizeof label, "%.2f N", q);
            labels.push_back({label, theme.cable, tip, d / dl, 4.0f});
        }
        // The contact frame at the platform's centre: t along the platform (toward the
        // fingertip), n into the finger; labelled with the text.
        const float axis = 0.35f * m.arrow_full;
        const P2 o_px = view.to_px(centre);
        const P2 t_px = view.to_px(centre + dir) - o_px, n_px = view.to_px(centre + (-std::sin(pd.roll) * t + std::cos(pd.roll) * n_in)) - o_px;
        const P2 t_end = o_px + t_px / glm::length(t_px) * axis, n_end = o_px + n_px / glm::length(n_px) * axis;
        arrow(o_px, t_end, m.outline_width, theme.legend, out);
        arrow(o_px, n_end, m.outline_width, theme.legend, out);
        marks.add_stroke(o_px, t_end, m.outline_width * 4.0f * 0.9f);
        marks.add_stroke(o_px, n_end, m.outline_width * 4.0f * 0.9f);
        // The axes' letters first (one character, beside their arrow's tip), then the tensions.
        labels.insert(labels.begin(), {{"n", theme.legend, n_end, n_px, 3.0f}, {"t", theme.legend, t_end, t_px, 3.0f}});
        // Away from the finger (n points into it), below the origin if there is room.
        labels.push_back({"contact frame", theme.legend, o_px, -n_px, 2.5f * m.dot_radius});
    }

    // Force on the finger, from the target site, full length at max force.
    const double f = glm::length(o.force);
    if (o.contact && f > 0.0 && c.max_force > 0.0) {
        const Vec2 dir = o.force / f;
        const float len = static_cast<float>(std::min(f / c.max_force, 1.0)) * m.arrow_full;
        const P2 to = target + P2(static_cast<float>(dir.x), static_cast<float>(-dir.y)) * len;
        arrow(target, to, m.arrow_width, theme.force, out);
        marks.add_stroke(target, to, m.arrow_width * 4.0f * 0.9f);
    }

    // Contacts on the contour, over the arrow.
    for (int i = 0; i < o.contact_count && i < static_cast<int>(o.contacts.size()); ++i) {
        out.fill_disc(view.to_px(o.contacts[i].point), m.dot_radius, theme.contact);
        marks.add_disc(view.to_px(o.contacts[i].point), m.dot_radius);
    }

    // Anticipation (free space): the expected contact on the contour, joined to the pad target.
    if (!o.contact && o.anticipating) {
        const P2 p = view.to_px(o.anticipated_point);
        out.line(target, p, m.outline_width * 0.75f, theme.anticipation.with_alpha(120));
        out.stroke_circle(p, m.dot_radius, m.outline_width, theme.anticipation);
        marks.add_stroke(target, p, m.outline_width * 0.75f);
        marks.add_disc(p, m.dot_radius + 0.5f * m.outline_width);
    }

    if (!c.text || labels.empty()) return;
    // The contour near the labels is data too: the environment's pieces within reach of the
    // candidates (the tree's box query), as px strokes.
    float reach = 0.0f;
    for (const PendingLabel& l : labels) {
        const P2 size = text_size(l.text, m.text_scale);
        reach = std::max(reach, 13.0f * l.gap + std::max(size.x, size.y));
    }
    LabelBox region{labels.front().anchor, labels.front().anchor};
    for (const PendingLabel& l : labels) region.lo = glm::min(region.lo, l.anchor), region.hi = glm::max(region.hi, l.anchor);
    region.lo -= P2(reach), region.hi += P2(reach);
    if (c.env) add_contour_marks(*c.env, view, region, m.contour_width, marks);
    for (const PendingLabel& l : labels) {
        const P2 size = text_size(l.text, m.text_scale);
        P2 at;
        if (place_label(marks, l.text, size, label_candidates(l.anchor, size, l.toward, l.gap), at))
            draw_text(out, at, l.text, l.color, m.text_scale);
    }
}

}  // namespace contactlab::render::parts
