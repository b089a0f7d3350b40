// label_place.cpp — free places for the canvas's labels (label_place.hpp).
#include "engine/render/label_place.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::render {
namespace {

// Whether segment a -> b comes within `r` px of the box (the box grown by r, Liang-Barsky clip of
// the segment against it; the grown box's rounded corners are taken square: a little more room).
bool segment_near_box(P2 a, P2 b, float r, const LabelBox& box) {
    const P2 lo = box.lo - P2(r), hi = box.hi + P2(r);
    float t0 = 0.0f, t1 = 1.0f;
    const P2 d = b - a;
    const float p[4] = {-d.x, d.x, -d.y, d.y};
    const float q[4] = {a.x - lo.x, hi.x - a.x, a.y - lo.y, hi.y - a.y};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0f) {
            if (q[i] < 0.0f) return false;  // parallel to this side and outside it
            continue;
        }
        const float t = q[i] / p[i];
        if (p[i] < 0.0f) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
        if (t0 > t1) return false;
    }
    return true;
}

}  // namespace

void LabelMarks::add_polyline(const std::vector<P2>& points, bool closed, float width) {
    for (std::size_t i = 1; i < points.size(); ++i) add_stroke(points[i - 1], points[i], width);
    if (closed && points.size() > 2) add_stroke(points.back(), points.front(), width);
}

bool LabelMarks::free(const LabelBox& box, float clearance) const {
    if (box.lo.x < area.lo.x || box.lo.y < area.lo.y || box.hi.x > area.hi.x || box.hi.y > area.hi.y) return false;
    const LabelBox grown{box.lo - P2(clearance), box.hi + P2(clearance)};
    for (const LabelBox& t : texts)
        if (grown.intersects(t)) return false;
    for (const LabelStroke& s : strokes)
        if (segment_near_box(s.a, s.b, s.half_width + clearance, box)) return false;
    return true;
}

std::vector<P2> label_candidates(P2 anchor, P2 size, P2 toward, float gap) {
    const float base = std::atan2(toward.y, toward.x);
    std::vector<P2> out;
    const P2 half = 0.5f * size;
    for (const float g : {gap, 2.0f * gap, 3.5f * gap, 5.5f * gap, 8.0f * gap, 12.0f * gap}) {
        // 0, +1, -1, +2, -2, ... sixteenths of a turn from `toward`.
        for (int k = 0; k < 16; ++k) {
            const int step = (k + 1) / 2 * (k % 2 ? 1 : -1);
            const float a = base + static_cast<float>(step) * (2.0f * 3.14159265f / 16.0f);
            const P2 u(std::cos(a), std::sin(a));
            // Centre far enough along u that the box's nearest side is g px from the anchor.
            const float reach = std::abs(u.x) * half.x + std::abs(u.y) * half.y;
            const P2 centre = anchor + u * (g + reach);
            out.push_back(centre - half);
        }
    }
    return out;
}

bool place_label(LabelMarks& marks, const std::string& text, P2 size, const std::vector<P2>& candidates, P2& at) {
    for (const P2& c : candidates) {
        const P2 lo(std::round(c.x), std::round(c.y));  // draw_text rounds its origin so
        const LabelBox box{lo, lo + size};
        if (!marks.free(box, kLabelClearance)) continue;
        marks.texts.push_back(box);
        marks.placed.push_back(text);
        at = box.lo;
        return true;
    }
    marks.dropped.push_back(text);
    return false;
}

}  // namespace contactlab::render
