// cspace.hpp — the configuration-space obstacle of the finger for one finger angle phi.
//
// Seed 000 §3.1: the finger angle is a driven coordinate, so for the current phi the obstacle is
// a 2-D region the finger centre x_f may not enter. Its boundary is made of pieces, each the set
// of centres at which one part of the pad touches one part of the contour:
//
//   source            pad part   contour part   c-space piece
//   line_offset       interior   line           the line shifted by R along its free normal
//   arc_offset        interior   arc            concentric arc of radius rho + R (bump) / rho - R (bowl)
//   vertex            interior   convex vertex  circle of radius R about the vertex
//   endpoint          an end     line or arc    the segment translated by -R u(theta_end)
//   vertex_inner      interior,  convex vertex  circle of radius R about the vertex, free inside
//                     concave side
//   arc_inner         interior,  bump, rho < R  concentric circle of radius R - rho, free inside
//                     concave side
//
// The pad is an arc, not a disc (seed 000: "the rest of the finger is disregarded"): pushed far
// past a thin wall or a sharp corner, the contour can come round a pad end and reach the pad from
// its concave side, behind it. The two inner sources are those contacts; without them the pad's
// end slid round the foot of a thin wall and the pad then cut through the wall (fuzz-contact).
// Lines cannot touch a circle from inside, and a bowl touching it from inside would already be
// penetrating, so only convex vertices and bumps tighter than the pad have inner pieces.
//
// Each piece exists only where the contact is locally non-penetrating (the contact normal inside
// the pad's span, the pad leaving an endpoint toward free space). Every piece lies in the closed
// obstacle, so a path that starts in free space meets the obstacle first on one of them.
#pragma once

#include "haptics/environment.hpp"
#include "haptics/finger.hpp"

#include <vector>

namespace contactlab {

struct CPiece {
    enum class Kind : std::uint8_t { line, circle };
    enum class Source : std::uint8_t { line_offset, arc_offset, vertex, endpoint, vertex_inner, arc_inner };
    Kind kind = Kind::line;
    Source source = Source::line_offset;
    int segment = -1;       // EnvSegment index this piece comes from (the vertex's owner for vertex)
    double pad_theta = 0;   // endpoint pieces: the pad end's angle (rad) as seen from x_f
    double pad_l = 0;       // endpoint pieces: its contact location (m), -L/2 or +L/2
    double contour_radius = 0;  // arc_offset: the contour arc's radius rho (m)

    // line pieces: from a along unit dir for len (m); free side along the unit normal n.
    Vec2 a{0.0}, dir{1.0, 0.0}, n{0.0, 1.0};
    double len = 0.0;

    // circle pieces: centre, radius (m), the CCW span of angles about the centre, and whether
    // free space is outside the circle.
    Vec2 center{0.0};
    double radius = 0.0;
    AngleSpan span;
    bool free_outside = true;
};

// What the pieces need of the pad at one finger angle, computed once per angle (the sines and
// cosines), not once per segment.
struct PadFrame {
    FingerShape finger;
    double phi = 0.0;         // rad
    AngleSpan span;           // pad angles that can touch
    Vec2 mid_dir{0.0, -1.0};  // unit direction of the pad's middle from x_f
    double cos_half = 0.0;    // cos of the pad's half-angle (-2 for a full circle: everything)
    double end_theta[2] = {0.0, 0.0};  // the pad ends' angles (rad): low, high
    Vec2 end_dir[2];                   // unit directions to the ends
    Vec2 end_tangent[2];               // direction in which the pad continues from each end
    double end_tangent_angle[2] = {0.0, 0.0};  // their angles (rad)
    double end_l[2] = {0.0, 0.0};      // the ends' contact locations (m): -L/2, +L/2
};
PadFrame make_pad_frame(const FingerShape& finger, double phi);

// Appends the pieces of segment `index` (and of the vertex at its end, and at its start for the
// first segment of an open chain) for the pad frame's finger angle.
void append_cspace_pieces(const Environment& env, int index, const PadFrame& pad, std::vector<CPiece>& out);
// The same for finger angle phi (rad): builds the pad frame first.
void append_cspace_pieces(const Environment& env, int index, const FingerShape& finger,
                          double phi, std::vector<CPiece>& out);

// Signed distance (m) from p to the piece's supporting line/circle, positive on the free side.
double piece_signed_distance(const CPiece& piece, Vec2 p);
// Free-side unit normal of the piece's supporting curve at p.
Vec2 piece_normal_at(const CPiece& piece, Vec2 p);

// The point of the piece nearest to p (clamped to the piece's extent), its parameter (m along a
// line, rad from span.start on a circle) and whether the clamp was active.
struct PieceFoot {
    Vec2 point{0.0};
    double param = 0.0;
    bool clamped = false;
};
PieceFoot piece_foot(const CPiece& piece, Vec2 p);
// Parameter of p (assumed on or near the piece), unclamped.
double piece_param(const CPiece& piece, Vec2 p);
// True when the parameter lies within the piece (with `slack` in its own units).
bool piece_param_inside(const CPiece& piece, double param, double slack);
Vec2 piece_point(const CPiece& piece, double param);
// Bounding box of the piece (m).
Aabb piece_box(const CPiece& piece);

// Where the pad touches the contour when x_f is at c on this piece (world point, m), and the
// contact location l (m) on the pad.
Vec2 piece_contact_point(const CPiece& piece, const FingerShape& finger, Vec2 c);
double piece_contact_location(const CPiece& piece, const FingerShape& finger, double phi, Vec2 c);

}  // namespace contactlab
