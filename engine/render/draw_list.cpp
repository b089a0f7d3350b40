// draw_list.cpp — anti-aliased strokes and fills as triangles (see draw_list.hpp).
#include "engine/render/draw_list.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace contactlab::render {
namespace {

constexpr float kMergeDistance = 1e-3f;  // px
constexpr float kMaxMiter = 4.0f;        // miter length limit, in half-widths
constexpr int kMaxChords = 8192;         // per arc, whatever its size on screen

P2 left_normal(P2 d) { return {-d.y, d.x}; }

// Copies `points` without near-duplicates (and without a closing duplicate when `closed`).
void dedupe(std::span<const P2> points, bool closed, std::vector<P2>& out) {
    out.clear();
    for (const P2& p : points)
        if (out.empty() || glm::length(p - out.back()) > kMergeDistance) out.push_back(p);
    if (closed) while (out.size() > 1 && glm::length(out.front() - out.back()) <= kMergeDistance) out.pop_back();
}

// Per-point offset direction for a polyline: the averaged left normals scaled to keep the stroke's
// width along both neighbouring segments (miter), limited to kMaxMiter.
void miter_normals(const std::vector<P2>& pts, bool closed, std::vector<P2>& out) {
    const size_t n = pts.size();
    out.assign(n, P2(0.0f));
    auto seg_normal = [&](size_t i) {  // left normal of segment i -> i+1 (wrapping)
        const P2 d = pts[(i + 1) % n] - pts[i];
        return left_normal(d / glm::length(d));
    };
    for (size_t i = 0; i < n; ++i) {
        const bool has_prev = closed || i > 0;
        const bool has_next = closed || i + 1 < n;
        const P2 n_prev = has_prev ? seg_normal((i + n - 1) % n) : seg_normal(i);
        const P2 n_next = has_next ? seg_normal(i) : n_prev;
        P2 m = n_prev + n_next;
        const float len = glm::length(m);
        if (len < 1e-6f) { out[i] = n_next; continue; }  // a full reversal: no sensible miter
        m /= len;
        const float cos_half = glm::dot(m, n_next);
        out[i] = m * std::min(1.0f / std::max(cos_half, 1e-6f), kMaxMiter);
    }
}

}  // namespace

void simplify_polyline(std::vector<P2>& pts, float tol) {
    if (pts.size() < 3) return;
    size_t out = 1;  // pts[0] stays; pts[out - 1] is the current anchor
    size_t i = 1;
    while (i < pts.size()) {
        const P2 anchor = pts[out - 1];
        // Directions (relative to the first point farther than tol) a chord from the anchor may
        // take and still pass within tol of every point since the anchor.
        bool have_ref = false;
        P2 ref(1.0f, 0.0f);
        double lo = -1e9, hi = 1e9;
        size_t j = i;
        for (; j < pts.size(); ++j) {
            const P2 d = pts[j] - anchor;
            const double len = glm::length(d);
            if (len <= tol) continue;
            if (!have_ref) {
                ref = d / static_cast<float>(len);
                have_ref = true;
            }
            const double a = std::atan2(static_cast<double>(ref.x) * d.y - static_cast<double>(ref.y) * d.x,
                                        static_cast<double>(ref.x) * d.x + static_cast<double>(ref.y) * d.y);
            if (a < lo || a > hi) break;  // the chord to pts[j] would leave a point behind
            const double slack = std::asin(std::min(1.0, tol / len));
            lo = std::max(lo, a - slack);
            hi = std::min(hi, a + slack);
        }
        // pts[j - 1] is the farthest point reachable by one chord: the next anchor.
        const size_t next = (j == pts.size()) ? pts.size() - 1 : std::max(j - 1, i);
        pts[out++] = pts[next];
        i = next + 1;
    }
    pts.resize(out);
}

int arc_chord_count(double r, double sweep, double tolerance_px) {
    sweep = std::abs(sweep);
    if (r <= tolerance_px || sweep == 0.0) return 1;
    // A chord spanning angle a deviates from the circle by r (1 - cos(a / 2)).
    const double max_step = 2.0 * std::acos(1.0 - tolerance_px / r);
    const double n = std::ceil(sweep / max_step);
    return static_cast<int>(std::clamp(n, 1.0, static_cast<double>(kMaxChords)));
}

void arc_points(P2 center, double r, double a0, double a1, double tolerance_px, std::vector<P2>& out) {
    const int n = arc_chord_count(r, a1 - a0, tolerance_px);
    for (int i = 0; i <= n; ++i) {
        const double a = a0 + (a1 - a0) * static_cast<double>(i) / n;
        out.push_back({static_cast<float>(center.x + r * std::cos(a)), static_cast<float>(center.y + r * std::sin(a))});
    }
}

void DrawList::clear() {
    vertices_.clear();
    indices_.clear();
    commands_.clear();
}

uint32_t DrawList::add_vertex(P2 p, Color c) {
    vertices_.push_back({p.x, p.y, c});
    return static_cast<uint32_t>(vertices_.size() - 1);
}

// Appends a command for indices [first_index, end), merging with the previous one when both are
// plain triangles (one draw call for a run of strokes and fills).
void DrawList::emit(DrawKind kind, uint32_t first_index) {
    const uint32_t count = static_cast<uint32_t>(indices_.size()) - first_index;
    if (count == 0) return;
    if (kind == DrawKind::triangles && !commands_.empty() && commands_.back().kind == DrawKind::triangles &&
        commands_.back().first_index + commands_.back().index_count == first_index) {
        commands_.back().index_count += count;
        return;
    }
    commands_.push_back({kind, first_index, count});
}

void DrawList::stroke(std::span<const P2> points, bool closed, float width, Color color) {
    dedupe(points, closed, scratch_points_);
    const auto& pts = scratch_points_;
    const size_t n = pts.size();
    if (n < 2 || width <= 0.0f) return;
    if (n == 2) closed = false;
    miter_normals(pts, closed, scratch_normals_);

    // Core half-width (full alpha) and the 1 px fringe beyond it; thinner than 1 px fades instead.
    const float core = std::max(0.5f * (width - 1.0f), 0.0f);
    const float fringe = core + 1.0f;
    Color solid = color;
    if (width < 1.0f) solid.a = static_cast<uint8_t>(std::lround(color.a * width));
    const Color clear = color.with_alpha(0);

    const uint32_t first_index = static_cast<uint32_t>(indices_.size());
    const uint32_t base = static_cast<uint32_t>(vertices_.size());
    for (size_t i = 0; i < n; ++i) {
        const P2 p = pts[i], m = scratch_normals_[i];
        add_vertex(p + m * fringe, clear);
        add_vertex(p + m * core, solid);
        add_vertex(p - m * core, solid);
        add_vertex(p - m * fringe, clear);
    }
    const size_t segments = closed ? n : n - 1;
    for (size_t s = 0; s < segments; ++s) {
        const uint32_t a = base + static_cast<uint32_t>(4 * s);
        const uint32_t b = base + static_cast<uint32_t>(4 * ((s + 1) % n));
        for (uint32_t k = 0; k < 3; ++k)  // the three strips: fringe, core, fringe
            indices_.insert(indices_.end(), {a + k, b + k, b + k + 1, a + k, b + k + 1, a + k + 1});
    }
    emit(DrawKind::triangles, first_index);
}

void DrawList::line(P2 a, P2 b, float width, Color color) {
    const P2 pts[2] = {a, b};
    stroke(pts, false, width, color);
}

void DrawList::fill_convex(std::span<const P2> points, Color color) {
    dedupe(points, true, scratch_points_);
    const size_t n = scratch_points_.size();
    if (n < 3) return;
    // Make the polygon counter-clockwise in the pixel frame's math sense so left normals point in.
    double area2 = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const P2 a = scratch_points_[i], b = scratch_points_[(i + 1) % n];
        area2 += static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y;
    }
    if (area2 < 0.0) std::reverse(scratch_points_.begin(), scratch_points_.end());
    miter_normals(scratch_points_, true, scratch_normals_);

    // Inner polygon shrunk by 0.5 px at full alpha, outer ring grown by 0.5 px at alpha 0.
    const uint32_t first_index = static_cast<uint32_t>(indices_.size());
    const uint32_t base = static_cast<uint32_t>(vertices_.size());
    const Color clear = color.with_alpha(0);
    for (size_t i = 0; i < n; ++i) {
        add_vertex(scratch_points_[i] + scratch_normals_[i] * 0.5f, color);  // inward (left)
        add_vertex(scratch_points_[i] - scratch_normals_[i] * 0.5f, clear);
    }
    for (uint32_t i = 1; i + 1 < n; ++i) indices_.insert(indices_.end(), {base, base + 2 * i, base + 2 * (i + 1)});
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t a = base + 2 * i, b = base + 2 * static_cast<uint32_t>((i + 1) % n);
        indices_.insert(indices_.end(), {a, b, b + 1, a, b + 1, a + 1});
    }
    emit(DrawKind::triangles, first_index);
}

void DrawList::fill_disc(P2 center, float r, Color color, float tolerance_px) {
    std::vector<P2> rim;
    const int n = std::max(arc_chord_count(r, 2.0 * std::numbers::pi, tolerance_px), 8);
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        rim.push_back({static_cast<float>(center.x + r * std::cos(a)), static_cast<float>(center.y + r * std::sin(a))});
    }
    fill_convex(rim, color);
}

void DrawList::stroke_circle(P2 center, float r, float width, Color color, float tolerance_px) {
    std::vector<P2> rim;
    const int n = std::max(arc_chord_count(r, 2.0 * std::numbers::pi, tolerance_px), 8);
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        rim.push_back({static_cast<float>(center.x + r * std::cos(a)), static_cast<float>(center.y + r * std::sin(a))});
    }
    stroke(rim, true, width, color);
}

void DrawList::fill_rect(P2 lo, P2 hi, Color color) {
    const uint32_t first_index = static_cast<uint32_t>(indices_.size());
    const uint32_t q = add_vertex(lo, color);
    add_vertex({hi.x, lo.y}, color);
    add_vertex(hi, color);
    add_vertex({lo.x, hi.y}, color);
    indices_.insert(indices_.end(), {q, q + 1, q + 2, q, q + 2, q + 3});
    emit(DrawKind::triangles, first_index);
}

void DrawList::fill_polygon(std::span<const P2> points, Color color) {
    dedupe(points, true, scratch_points_);
    const size_t n = scratch_points_.size();
    if (n < 3) return;
    // Stencil pass: a fan from the first point; each triangle adds its winding to the stencil.
    uint32_t first_index = static_cast<uint32_t>(indices_.size());
    const uint32_t base = static_cast<uint32_t>(vertices_.size());
    P2 lo(static_cast<float>(width_), static_cast<float>(height_)), hi(0.0f);
    for (const P2& p : scratch_points_) {
        add_vertex(p, color);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    for (uint32_t i = 1; i + 1 < n; ++i) indices_.insert(indices_.end(), {base, base + i, base + i + 1});
    emit(DrawKind::stencil_mark, first_index);

    // Cover pass: the polygon's bounds (clamped to the image) where the stencil is not zero.
    lo = glm::max(lo, P2(0.0f));
    hi = glm::min(hi, P2(static_cast<float>(width_), static_cast<float>(height_)));
    if (lo.x >= hi.x || lo.y >= hi.y) {  // off screen: the marks still need clearing
        lo = P2(0.0f);
        hi = P2(static_cast<float>(width_), static_cast<float>(height_));
    }
    first_index = static_cast<uint32_t>(indices_.size());
    const uint32_t q = add_vertex(lo, color);
    add_vertex({hi.x, lo.y}, color);
    add_vertex(hi, color);
    add_vertex({lo.x, hi.y}, color);
    indices_.insert(indices_.end(), {q, q + 1, q + 2, q, q + 2, q + 3});
    emit(DrawKind::stencil_cover, first_index);
}

}  // namespace contactlab::render
