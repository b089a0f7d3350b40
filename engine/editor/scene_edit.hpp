// scene_edit.hpp — the authoring operations on a Scene, as pure functions (the editor's tools
// call them and hand the result to Document::edit): handles (segment end points and Bezier
// control points), picking, moving a handle with its joined neighbour, adding a line (a new chain
// or appended to an open chain's end), deleting a segment.
#pragma once

#include "haptics/scene.hpp"

#include <optional>
#include <string>

namespace contactlab::editor {

// A point of the geometry the user can grab. `point` indexes the segment's points in travel
// order: line 0 = from, 1 = to; quad p0, p1, p2; cubic p0..p3; arc 0 = start, 1 = the point
// halfway along, 2 = end (moving one refits the arc through the three, the others kept).
struct Handle {
    int contour = -1;
    int segment = -1;
    int point = -1;
    bool operator==(const Handle&) const = default;
};

int handle_count(const Segment& s);              // points of a segment
bool valid_handle(const Scene& scene, const Handle& h);  // names an existing point
Vec2 handle_position(const Scene& scene, const Handle& h);
bool handle_is_end(const Scene& scene, const Handle& h);  // first or last point of its segment

// The handle nearest `p` within `radius` (m); end points win ties over control points.
std::optional<Handle> pick_handle(const Scene& scene, Vec2 p, double radius);
// The open chain end (first point of its first segment or last of its last) within `radius` (m).
std::optional<Handle> pick_open_end(const Scene& scene, Vec2 p, double radius);

// Moves the handle to `to` (m). An end point shared with the neighbouring segment (joined chain,
// also across a closed contour's seam) moves with it, so chains stay joined.
Scene move_handle(const Scene& scene, const Handle& h, Vec2 to);

// A line from `a` to `b` (m). If `a` is an open chain's last point it is appended there; if it is
// a chain's first point the line is prepended (travelling from b to a, so the chain's direction,
// and with it the solid side, is kept); a chain whose ends meet that way becomes closed. Otherwise
// it starts a new open contour.
Scene add_line(const Scene& scene, Vec2 a, Vec2 b, double join_radius);
// The same for any segment (travelling from segment_start to segment_end).
Scene add_segment(const Scene& scene, const Segment& segment, double join_radius);

// The circular arc from a through m to b (m); nullopt when the points are (nearly) collinear or
// coincide. Its end points are a and b to rounding (cos/sin of the angles).
std::optional<ArcSegment> arc_through(Vec2 a, Vec2 m, Vec2 b);

// Tangent continuation (G1 joints). The direction (unit) a new segment starting at the open chain
// end within `radius` (m) of p must leave in to join it with a continuous tangent: the chain's end
// tangent at its last point, the reverse of its start tangent at its first point; nullopt when p
// is no open chain end.
std::optional<Vec2> continuation_tangent(const Scene& scene, Vec2 p, double radius);
// p projected onto the ray from origin along unit dir (never behind the origin) / onto the line
// through origin normal to dir (where the centre of a tangent arc lies).
Vec2 project_on_ray(Vec2 origin, Vec2 dir, Vec2 p);
Vec2 project_on_normal(Vec2 origin, Vec2 dir, Vec2 p);
// The arc about `center` from `start` (radius |start - center|) to where the ray toward `end`
// meets the circle, counter-clockwise (dir > 0), clockwise (dir < 0) or the short way (dir 0);
// nullopt for a zero radius or a zero sweep.
std::optional<ArcSegment> arc_center_radius(Vec2 start, Vec2 center, Vec2 end, int dir);
// The arc leaving `start` along unit `tangent` (G1), on the circle that also passes through
// `through`, to where the ray from its centre toward `end` meets it; nullopt when `through` is on
// the tangent line (that continuation is a straight line).
std::optional<ArcSegment> tangent_arc_through(Vec2 start, Vec2 tangent, Vec2 through, Vec2 end);

// Removes one segment. A chain broken in the middle becomes two open chains; a closed contour
// becomes one open chain starting after the gap; an empty contour disappears.
Scene delete_segment(const Scene& scene, int contour, int segment);

// Reverses a contour's direction of travel (flips the solid side).
Scene reverse_contour(const Scene& scene, int contour);

// Opens a closed contour (its segments kept: the seam becomes the open chain's two ends), or
// closes an open one: its ends joined as they are when they meet (within kSceneJoinTolerance),
// otherwise by a new line from its last point back to its first.
Scene toggle_closed(const Scene& scene, int contour);

// Total number of segments (for the status line and tests).
int segment_count(const Scene& scene);

}  // namespace contactlab::editor
