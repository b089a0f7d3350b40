// frame_overlays.cpp — overlays for the finger's current angle: the c-space obstacle boundary
// (seed 000 Fig. 5) and the anticipation zones (Fig. 6).
#include "engine/render/frame_parts.hpp"

#include "haptics/cspace.hpp"

#include <cmath>
#include <limits>

namespace contactlab::render::parts {
namespace {

constexpr int kZoneCell = 4;             // px per zone cell side
constexpr size_t kMaxZonePieces = 4096;  // beyond this the zone overlay is skipped (cost)

// C-space pieces of every segment near the view, for the finger's phi.
void pieces_in_view(const FrameContent& c, const View& view, std::vector<CPiece>& pieces) {
    Aabb box = view.world_bounds();
    const double R = c.shape.radius;
    box.lo -= Vec2(2.0 * R);
    box.hi += Vec2(2.0 * R);
    std::vector<int> ids;
    c.env->tree.query(box, ids);
    std::sort(ids.begin(), ids.end());
    for (int id : ids) append_cspace_pieces(*c.env, id, c.shape, c.finger->phi, pieces);
}

}  // namespace

void draw_cspace(const FrameContent& c, const View& view, const Theme& theme, const Metrics& m, DrawList& out) {
    std::vector<CPiece> pieces;
    pieces_in_view(c, view, pieces);
    std::vector<P2> pts;
    for (const CPiece& p : pieces) {
        pts.clear();
        if (p.kind == CPiece::Kind::line) {
            pts.push_back(view.to_px(p.a));
            pts.push_back(view.to_px(p.a + p.dir * p.len));
        } else {
            const double a0 = p.span.start, a1 = p.span.start + p.span.width;
            const int n = arc_chord_count(p.radius * view.px_per_m, a1 - a0, kFlattenTolerancePx);
            for (int i = 0; i <= n; ++i) pts.push_back(view.to_px(p.center + p.radius * unit_at(a0 + (a1 - a0) * i / n)));
        }
        out.stroke(pts, false, m.outline_width, theme.cspace);
    }
}

void draw_zones(const FrameContent& c, const View& view, const Theme& theme, DrawList& out) {
    std::vector<CPiece> pieces;
    pieces_in_view(c, view, pieces);
    if (pieces.empty() || pieces.size() > kMaxZonePieces) return;
    // Each cell takes the kind of contact its nearest c-space piece would make: the pad's interior,
    // or its proximal (l < 0) or distal (l > 0) end. Runs of equal cells in a row are merged.
    const Color colors[3] = {theme.zone_pad, theme.zone_proximal, theme.zone_distal};
    auto zone_at = [&](Vec2 p) {
        double best = std::numeric_limits<double>::infinity();
        int zone = 0;
        for (const CPiece& piece : pieces) {
            const double d = glm::length(piece_foot(piece, p).point - p);
            if (d >= best) continue;
            best = d;
            zone = piece.source == CPiece::Source::endpoint ? (piece.pad_l < 0.0 ? 1 : 2) : 0;
        }
        return zone;
    };
    for (int y = 0; y < view.height; y += kZoneCell) {
        const float y0 = static_cast<float>(y), y1 = static_cast<float>(std::min(y + kZoneCell, view.height));
        int run_start = 0, run_zone = -1;
        for (int x = 0; x <= view.width; x += kZoneCell) {
            const int zone = x < view.width ? zone_at(view.to_world(x + 0.5 * kZoneCell, y + 0.5 * kZoneCell)) : -2;
            if (zone == run_zone) continue;
            if (run_zone >= 0) {
                const float x0 = static_cast<float>(run_start), x1 = static_cast<float>(std::min(x, view.width));
                out.fill_rect({x0, y0}, {x1, y1}, colors[run_zone]);
            }
            run_start = x;
            run_zone = zone;
        }
    }
}

}  // namespace contactlab::render::parts
