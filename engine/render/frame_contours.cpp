// frame_contours.cpp — contours flattened to the pixel tolerance, their solid side filled.
//
// Closed contours are filled inside. An open (terrain) chain is filled on its solid side (the
// right of travel) down to beyond the view's edge: the polygon is the chain, then from its end
// out along the axis direction nearest the chord's right normal (straight down for a terrain
// drawn left to right), across to the same distance beyond the start, and back to the start. A chain that
// crosses itself or the sweep is filled by the nonzero rule. The fill's edge is aliased
// (stencil); the anti-aliased contour stroke covers it.
#include "engine/render/frame_parts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <variant>

namespace contactlab::render::parts {
namespace {

// Dense contours are simplified to this (px); well below the flattening tolerance.
constexpr float kSimplifyTolerancePx = 0.05f;

// Right-hand (solid-side) normal of a unit direction of travel.
Vec2 solid_normal(Vec2 t) { return {t.y, -t.x}; }

}  // namespace

namespace {

// Points of a Bezier curve given by its control points (world, m), flattened for the view: with
// n uniform steps the chord error is at most max|B''| / (8 n^2), so n follows from the tolerance.
template <size_t N>
void flatten_bezier(const std::array<Vec2, N>& ctrl, const View& view, bool skip_first, std::vector<P2>& out) {
    double second = 0.0;  // bound on |B''| (px)
    for (size_t i = 0; i + 2 < N; ++i)
        second = std::max(second, (N - 1) * (N - 2) * glm::length(ctrl[i] - 2.0 * ctrl[i + 1] + ctrl[i + 2]));
    second *= view.px_per_m;
    const double n = std::ceil(std::sqrt(second / (8.0 * kFlattenTolerancePx)));
    const int steps = static_cast<int>(std::clamp(n, 1.0, 8192.0));
    for (int k = skip_first ? 1 : 0; k <= steps; ++k) {
        // de Casteljau at s = k / steps.
        const double t = static_cast<double>(k) / steps;
        std::array<Vec2, N> q = ctrl;
        for (size_t level = N - 1; level > 0; --level)
            for (size_t i = 0; i < level; ++i) q[i] = (1.0 - t) * q[i] + t * q[i + 1];
        out.push_back(view.to_px(q[0]));
    }
}

}  // namespace

void flatten_segment(const Segment& segment, const View& view, bool skip_first, std::vector<P2>& out) {
    std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, LineSegment>) {
                if (!skip_first) out.push_back(view.to_px(s.from));
                out.push_back(view.to_px(s.to));
            } else if constexpr (std::is_same_v<S, ArcSegment>) {
                const int n = arc_chord_count(s.radius * view.px_per_m, s.end_angle - s.start_angle, kFlattenTolerancePx);
                for (int i = skip_first ? 1 : 0; i <= n; ++i) {
                    const double a = s.start_angle + (s.end_angle - s.start_angle) * static_cast<double>(i) / n;
                    out.push_back(view.to_px(s.center + s.radius * unit_at(a)));
                }
            } else if constexpr (requires { s.p3; }) {  // cubic Bezier
                flatten_bezier(std::array<Vec2, 4>{s.p0, s.p1, s.p2, s.p3}, view, skip_first, out);
            } else {  // quadratic Bezier
                flatten_bezier(std::array<Vec2, 3>{s.p0, s.p1, s.p2}, view, skip_first, out);
            }
        },
        segment);
}

void flatten_contour(const Contour& contour, const View& view, std::vector<P2>& out) {
    out.clear();
    for (size_t i = 0; i < contour.segments.size(); ++i) flatten_segment(contour.segments[i], view, i > 0, out);
    // Many segments per pixel (dense terrains): keep what the pixels can show.
    if (out.size() > 2 * static_cast<size_t>(view.width + view.height)) simplify_polyline(out, kSimplifyTolerancePx);
}

void draw_solids(const Scene& scene, const View& view, const Theme& theme, const Metrics& m, DrawList& out) {
    // Each contour flattened once, for its fill and its stroke.
    std::vector<std::vector<P2>> outlines(scene.contours.size());
    for (size_t i = 0; i < scene.contours.size(); ++i) flatten_contour(scene.contours[i], view, outlines[i]);
    const Aabb b = view.world_bounds();
    const double beyond = 2.0 * glm::length(b.hi - b.lo);  // m: well past every edge of the view
    // Fills first, so no fill covers another contour's stroke.
    std::vector<P2> pts;
    for (size_t i = 0; i < scene.contours.size(); ++i) {
        const Contour& contour = scene.contours[i];
        if (contour.segments.empty()) continue;
        pts = outlines[i];
        if (!contour.closed) {
            // Swept from the chain in one direction past the view's edge: the axis direction
            // nearest the chord's right normal, i.e. straight down for a terrain drawn left to
            // right, up for a ceiling drawn right to left. Each end's own normal (as before) made
            // a chain that rises or tilts at its ends, like seed 002's bump stimuli, fill a
            // crossed polygon: the nonzero rule then left most of the solid under the surface
            // empty, a sliver along it (issue 19).
            const Vec2 start = segment_start(contour.segments.front());
            const Vec2 end = segment_end(contour.segments.back());
            Vec2 normal = solid_normal(end - start);
            if (!(glm::length(normal) > 1e-12)) {  // the chain comes back to its start: its ends' normals
                normal = solid_normal(segment_start_tangent(contour.segments.front())) +
                         solid_normal(segment_end_tangent(contour.segments.back()));
            }
            const Vec2 down = std::abs(normal.x) > std::abs(normal.y) ? Vec2{normal.x > 0.0 ? 1.0 : -1.0, 0.0}
                                                                      : Vec2{0.0, normal.y > 0.0 ? 1.0 : -1.0};
            // Far points measured from the view's centre distance, so they always leave the view.
            const double reach = beyond + glm::length(end - view.center) + glm::length(start - view.center);
            pts.push_back(view.to_px(end + down * reach));
            pts.push_back(view.to_px(start + down * reach));
        }
        out.fill_polygon(pts, theme.solid_fill);
    }
    for (size_t i = 0; i < scene.contours.size(); ++i)
        if (!scene.contours[i].segments.empty()) out.stroke(outlines[i], scene.contours[i].closed, m.contour_width, theme.contour);
}

}  // namespace contactlab::render::parts
