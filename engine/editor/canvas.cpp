// canvas.cpp — tools, pan/zoom, finger and the editor's marks (see canvas.hpp).
#include "engine/editor/canvas.hpp"

#include "engine/render/frame_parts.hpp"
#include "haptics/stimuli.hpp"

#include <cmath>

namespace contactlab::editor {
namespace {

constexpr double kPickPx = 8.0;  // px: how close the pointer must be to grab a point

double pick_radius(const EditorState& s) { return kPickPx / s.camera.view().px_per_m; }  // m

// The world point under (x, y) px; on the grid when snapping is on (authoring tools only).
Vec2 world_at(const EditorState& s, double x, double y) {
    Vec2 w = s.camera.view().to_world(x, y);
    if (s.snap_grid && s.tool != Tool::finger && s.grid_mm > 0.0) {
        const double g = s.grid_mm * 1e-3;
        w = {std::round(w.x / g) * g, std::round(w.y / g) * g};
    }
    return w;
}

// Line tool: a point near an existing segment end snaps onto it (so chains join exactly).
Vec2 snap_to_ends(const EditorState& s, Vec2 p) {
    if (auto h = pick_handle(s.doc.scene(), p, pick_radius(s)); h && handle_is_end(s.doc.scene(), *h))
        return handle_position(s.doc.scene(), *h);
    return p;
}

void publish_pose(EditorState& s) {
    if (s.pose_input) s.pose_input->set_pose(s.pose);
}

std::size_t points_needed(Tool t) {
    switch (t) {
        case Tool::line: return 2;
        case Tool::cubic: return 4;
        default: return 3;  // quad, arc, arc_center
    }
}

// The direction the segment being drawn must leave its start in for a G1 joint, when tangent
// snapping is on and it starts on an open chain's end (snap_to_ends put it there exactly).
std::optional<Vec2> draw_tangent(const EditorState& s) {
    if (!s.snap_tangent || s.pending.empty()) return std::nullopt;
    return continuation_tangent(s.doc.scene(), s.pending.front(), 1e-9);
}

// Where the k-th click (k >= 1) lands with tangent snapping: the second point of a line, a curve
// (its first control point) on the tangent ray; a centre-radius arc's centre on the normal.
Vec2 snap_click(const EditorState& s, std::size_t k, Vec2 p) {
    const auto t = draw_tangent(s);
    if (!t || k != 1) return p;
    const Vec2 a = s.pending.front();
    switch (s.tool) {
        case Tool::line:
        case Tool::quad:
        case Tool::cubic: return project_on_ray(a, *t, p);
        case Tool::arc_center: return project_on_normal(a, *t, p);
        default: return p;
    }
}

// The segment the current tool makes of its points q (all of them); nullopt when none exists.
std::optional<Segment> build_segment(const EditorState& s, const std::vector<Vec2>& q) {
    const auto t = draw_tangent(s);
    switch (s.tool) {
        case Tool::line: return LineSegment{q[0], q[1]};
        case Tool::quad: return QuadSegment{q[0], q[1], q[2]};
        case Tool::cubic: return CubicSegment{q[0], q[1], q[2], q[3]};
        case Tool::arc: {
            const auto arc = t ? tangent_arc_through(q[0], *t, q[1], q[2]) : arc_through(q[0], q[1], q[2]);
            if (arc) return *arc;
            return std::nullopt;
        }
        case Tool::arc_center: {
            // Tangent: turn toward the side the centre is on; otherwise the short way round.
            const int dir = t ? (glm::dot(q[1] - q[0], Vec2(-t->y, t->x)) > 0.0 ? 1 : -1) : 0;
            if (const auto arc = arc_center_radius(q[0], q[1], q[2], dir)) return *arc;
            return std::nullopt;
        }
        default: return std::nullopt;
    }
}

// Drawing tools: one more point; once the tool has all it needs the segment is added (an
// undoable edit) and its end starts the next segment of the chain.
void place_point(EditorState& s, Vec2 p) {
    if (!s.pending.empty()) p = snap_click(s, s.pending.size(), p);
    if (!s.pending.empty() && glm::length(p - s.pending.back()) < 1e-9) return;  // double click
    if (s.pending.size() + 1 < points_needed(s.tool)) {
        s.pending.push_back(p);
        return;
    }
    std::vector<Vec2> q = s.pending;
    q.push_back(p);
    const std::optional<Segment> seg = build_segment(s, q);
    if (!seg) {
        if (s.tool == Tool::arc_center) s.say("centre-radius arc: the centre is on the start, or the end is on the centre", true);
        else if (draw_tangent(s)) s.say("tangent arc: the through point is on the tangent line (that continuation is a line)", true);
        else s.say("arc: the three points are in a line; click a through point off the chord", true);
        s.pending.resize(1);
        return;
    }
    s.doc.edit(add_segment(s.doc.scene(), *seg, 1e-9), std::string("add ") + to_string(s.tool));
    s.say(std::string(to_string(s.tool)) + " added: " + std::to_string(segment_count(s.doc.scene())) + " segments");
    s.pending.assign(1, segment_end(*seg));  // chain: the next segment continues from here
}

}  // namespace

const char* to_string(Tool t) {
    switch (t) {
        case Tool::finger: return "finger";
        case Tool::select: return "select";
        case Tool::line: return "line";
        case Tool::quad: return "quad";
        case Tool::arc: return "arc";
        case Tool::arc_center: return "arc_center";
        case Tool::cubic: return "cubic";
    }
    return "?";
}

void canvas_move(EditorState& s, double x, double y) {
    if (s.panning) {
        s.camera.pan(x - s.pan_last_x, y - s.pan_last_y);
        s.pan_last_x = x;
        s.pan_last_y = y;
    }
    s.cursor = world_at(s, x, y);
    switch (s.tool) {
        case Tool::finger:
            s.pose.finger = s.camera.view().to_world(x, y);
            publish_pose(s);
            break;
        case Tool::select:
            if (s.dragging && s.selected) {
                // Only real moves count: a click (press and release in place) records no edit.
                const Vec2 to = s.cursor + s.grab_offset;
                if (handle_position(s.doc.scene(), *s.selected) != to)
                    s.doc.update_continuous(move_handle(s.drag_base, *s.selected, to));
            } else {
                s.hovered = pick_handle(s.doc.scene(), s.cursor, pick_radius(s));
            }
            break;
        case Tool::line:
        case Tool::quad:
        case Tool::arc:
        case Tool::arc_center:
        case Tool::cubic:
            s.hovered = pick_handle(s.doc.scene(), s.cursor, pick_radius(s));
            break;
    }
}

void canvas_press(EditorState& s, Button b, double x, double y) {
    canvas_move(s, x, y);
    if (b == Button::middle || (b == Button::right && s.pending.empty())) {
        s.panning = true;
        s.pan_last_x = x;
        s.pan_last_y = y;
        return;
    }
    if (b == Button::right) {  // drawing tools: end the chain
        s.pending.clear();
        return;
    }
    switch (s.tool) {
        case Tool::finger: break;
        case Tool::select:
            s.selected = pick_handle(s.doc.scene(), s.cursor, pick_radius(s));
            if (s.selected) {
                s.dragging = true;
                // Grabbed a few px off the point: it keeps that offset (no jump on a click).
                s.grab_offset = handle_position(s.doc.scene(), *s.selected) - s.cursor;
                if (s.snap_grid) s.grab_offset = Vec2(0.0);  // on the grid, the point goes to the grid
                s.doc.begin_continuous("move point");
                s.drag_base = s.doc.scene();
            }
            break;
        case Tool::line:
        case Tool::quad:
        case Tool::arc:
        case Tool::arc_center:
        case Tool::cubic: place_point(s, snap_to_ends(s, s.cursor)); break;
    }
}

void canvas_release(EditorState& s, Button b, double x, double y) {
    canvas_move(s, x, y);
    if (b != Button::left) {
        s.panning = false;
        return;
    }
    if (s.dragging) {
        s.dragging = false;
        s.doc.end_continuous();
    }
}

void canvas_wheel(EditorState& s, double x, double y, double notches, bool rotate) {
    if (rotate) {
        cmd_rotate_finger(s, notches * s.phi_step);
        return;
    }
    s.camera.zoom_at(x, y, std::pow(1.15, notches));
}

void cmd_rotate_finger(EditorState& s, double dphi) {
    s.pose.phi = std::remainder(s.pose.phi + dphi, 2.0 * kPi);
    publish_pose(s);
}

void cmd_undo(EditorState& s) {
    const std::string what = s.doc.undo_label();
    if (s.doc.undo()) s.say("undone: " + what);
    else s.say("nothing to undo");
    s.selected.reset();
}

void cmd_redo(EditorState& s) {
    const std::string what = s.doc.redo_label();
    if (s.doc.redo()) s.say("redone: " + what);
    else s.say("nothing to redo");
    s.selected.reset();
}

void cmd_delete(EditorState& s) {
    if (!s.selected) {
        s.say("select a point of the segment to delete first", true);
        return;
    }
    s.doc.edit(delete_segment(s.doc.scene(), s.selected->contour, s.selected->segment), "delete segment");
    s.selected.reset();
    s.hovered.reset();
    s.say("segment deleted");
}

void cmd_fit(EditorState& s) {
    const Scene& scene = s.doc.scene();
    Aabb box;
    for (int c = 0; c < static_cast<int>(scene.contours.size()); ++c) {
        const auto& segs = scene.contours[c].segments;
        for (int k = 0; k < static_cast<int>(segs.size()); ++k) {
            if (const auto* a = std::get_if<ArcSegment>(&segs[k])) {
                box.grow(a->center - Vec2(a->radius));
                box.grow(a->center + Vec2(a->radius));
            }
            box.grow(segment_start(segs[k]));
            box.grow(segment_end(segs[k]));
            for (int i = 0; i < handle_count(segs[k]); ++i) box.grow(handle_position(scene, {c, k, i}));
        }
    }
    const double reach = 3.5 * scene.finger.radius;  // m: the finger's body behind its centre
    // The finger where it is drawn: the cursor's pose, or (replay, USB: the cursor does not move
    // it) the device's.
    const Vec2 finger = (s.pose_input && s.pose_input->takes_position()) || !s.servo || s.servo->snapshot().ticks == 0
                           ? s.pose.finger
                           : s.servo->snapshot().finger;
    box.grow(finger - Vec2(reach));
    box.grow(finger + Vec2(reach));
    s.camera.fit(box);
}

void cmd_zoom_fingertip(EditorState& s) {
    const Vec2 finger = (s.pose_input && s.pose_input->takes_position()) || !s.servo || s.servo->snapshot().ticks == 0
                           ? s.pose.finger
                           : s.servo->snapshot().finger;
    s.camera.fit(render::fingertip_box(finger, s.pose.phi, s.doc.scene().finger.radius));  // as `render --wearable`
    s.say("zoomed on the fingertip (F: the whole scene)");
}

void cmd_toggle_stop(EditorState& s) {
    if (!s.servo) return;
    if (s.servo->stopped()) {
        s.servo->release_stop();
        s.say("emergency stop released: the servo re-arms (force ramps in once it is small)");
    } else {
        s.servo->engage_stop();
        s.say("EMERGENCY STOP: output zeroed", true);
    }
}

void cmd_save(EditorState& s, const std::string& path) {
    try {
        s.doc.save(path);
        s.say("saved " + s.doc.path());
    } catch (const std::exception& e) {
        s.say(e.what(), true);
    }
}

bool cmd_generate(EditorState& s, const std::string& name) {
    Scene g;
    try {
        if (name == "block") g = generate_block(0.06);          // seed 000 Fig. 9, d = 6 cm
        else if (name == "bumps") g = generate_bumps(BumpsDef{}).scene;  // seed 002
        else if (name == "arc") g = generate_arc(0.30, 0.020);  // seed 003: chord 30 cm, h 20 mm
        else return false;
    } catch (const std::exception& e) {
        s.say(std::string("generate: ") + e.what(), true);
        return true;
    }
    const Scene& cur = s.doc.scene();
    g.finger = cur.finger;
    g.force = cur.force;
    g.contact_location = cur.contact_location;
    s.doc.edit(std::move(g), "generate " + name);
    s.selected.reset();
    s.hovered.reset();
    cmd_fit(s);
    s.say("generated " + name + ": " + std::to_string(segment_count(s.doc.scene())) + " segments");
    return true;
}

bool canvas_key(EditorState& s, const std::string& name) {
    if (name == "space") cmd_toggle_stop(s);
    else if (name == "delete") cmd_delete(s);
    else if (name == "ctrl+z") cmd_undo(s);
    else if (name == "ctrl+y") cmd_redo(s);
    else if (name == "ctrl+s") cmd_save(s, {});
    else if (name == "escape") s.pending.clear();
    else if (name == "f") cmd_fit(s);
    else if (name == "z") cmd_zoom_fingertip(s);
    else if (name == "1") cmd_set_tool(s, Tool::finger);
    else if (name == "2") cmd_set_tool(s, Tool::select);
    else if (name == "3") cmd_set_tool(s, Tool::line);
    else if (name == "4") cmd_set_tool(s, Tool::quad);
    else if (name == "5") cmd_set_tool(s, Tool::arc);
    else if (name == "6") cmd_set_tool(s, Tool::arc_center);
    else if (name == "7") cmd_set_tool(s, Tool::cubic);
    else if (name == "q") cmd_rotate_finger(s, s.phi_step);
    else if (name == "e") cmd_rotate_finger(s, -s.phi_step);
    else return false;
    return true;
}

void cmd_set_tool(EditorState& s, Tool t) {
    if (s.dragging) canvas_release(s, Button::left, 0.0, 0.0);
    s.tool = t;
    s.pending.clear();
    s.dragging = false;
    s.hovered.reset();
}

void draw_canvas_marks(const EditorState& s, const render::Theme& theme, render::DrawList& out) {
    const render::View& view = s.camera.view();
    const Scene& scene = s.doc.scene();
    const render::Color handle_col = theme.legend.with_alpha(200);
    const render::Color accent{255, 200, 40, 255};
    const render::Color bad{235, 70, 60, 255};

    // An invalid scene is not what the frame shows (it draws the last valid one): outline the
    // user's current geometry in red so the edit is still visible.
    if (!s.doc.valid()) {
        std::vector<render::P2> pts;
        for (const Contour& c : scene.contours) {
            pts.clear();
            for (std::size_t i = 0; i < c.segments.size(); ++i)
                render::parts::flatten_segment(c.segments[i], view, i > 0, pts);
            if (pts.size() >= 2) out.stroke(pts, false, 2.0f, bad);
        }
        // Closed contours that cross: a ring where, so the crossing is found in a dense drawing.
        if (const auto& at = s.doc.problem_point()) out.stroke_circle(view.to_px(*at), 9.0f, 2.0f, bad);
    }
    if (s.tool != Tool::finger) {
        // Handles: end points as squares, Bezier control points as small discs with their arms.
        for (int c = 0; c < static_cast<int>(scene.contours.size()); ++c) {
            const auto& segs = scene.contours[c].segments;
            for (int k = 0; k < static_cast<int>(segs.size()); ++k) {
                const int n = handle_count(segs[k]);
                for (int i = 0; i < n; ++i) {
                    const Handle h{c, k, i};
                    const render::P2 p = view.to_px(handle_position(scene, h));
                    if (i == 0 || i == n - 1) {
                        out.fill_rect(p - render::P2(3.0f), p + render::P2(3.0f), handle_col);
                    } else {
                        const render::P2 q = view.to_px(handle_position(scene, {c, k, i < n / 2 + 1 ? 0 : n - 1}));
                        out.line(p, q, 1.0f, handle_col.with_alpha(120));
                        out.fill_disc(p, 3.0f, handle_col);
                    }
                }
            }
        }
        if (s.hovered) out.stroke_circle(view.to_px(handle_position(scene, *s.hovered)), 7.0f, 1.5f, accent);
        if (s.selected) {
            const render::P2 p = view.to_px(handle_position(scene, *s.selected));
            out.fill_rect(p - render::P2(5.0f), p + render::P2(5.0f), accent);
        }
    }
    if (s.device && std::string(s.device->name()).rfind("usb:", 0) == 0) {
        // A real device's workspace (e.g. the 2DIY's 12 x 7 cm), where its finger can go: the
        // scene outside it cannot be touched with this device.
        const Aabb w = s.device->limits().workspace;
        if (w.lo.x < w.hi.x && w.lo.y < w.hi.y) {
            const std::vector<render::P2> box = {view.to_px(w.lo), view.to_px(Vec2{w.hi.x, w.lo.y}), view.to_px(w.hi),
                                                 view.to_px(Vec2{w.lo.x, w.hi.y})};
            out.stroke(box, true, 1.5f, theme.legend.with_alpha(150));
        }
    }
    if (s.pose_input && s.device && std::string(s.device->name()) == "sim-cld") {
        // sim-cld: the cursor is where the hand wants the finger; the finger drawn by the frame is
        // where the simulation put it. A cross marks the former so the lag and the stop at the
        // surface can be seen.
        const render::P2 c = view.to_px(s.pose.finger);
        out.line(c - render::P2(9.0f, 0.0f), c + render::P2(9.0f, 0.0f), 1.5f, accent);
        out.line(c - render::P2(0.0f, 9.0f), c + render::P2(0.0f, 9.0f), 1.5f, accent);
    }
    if (!s.pending.empty()) {
        // The segment being drawn, as it would be with the cursor as its next point; until the
        // tool has all its points, their polygon.
        std::vector<render::P2> pts;
        std::vector<Vec2> q = s.pending;
        q.push_back(snap_click(s, s.pending.size(), s.cursor));
        if (q.size() == points_needed(s.tool)) {
            if (const auto seg = build_segment(s, q)) render::parts::flatten_segment(*seg, view, false, pts);
        } else {
            for (const Vec2& p : q) pts.push_back(view.to_px(p));
        }
        if (pts.size() >= 2) out.stroke(pts, false, 2.0f, accent.with_alpha(200));
        for (const Vec2& p : s.pending) out.fill_disc(view.to_px(p), 4.0f, accent);
    }
}

}  // namespace contactlab::editor
