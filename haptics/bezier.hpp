// bezier.hpp — quadratic and cubic Bezier curves: evaluation, nearest point, and conversion to
// the lines and arcs the proxy works with.
//
// Two conversions, one exact-by-default and one fast (issue #3's accuracy modes):
//   * arc spline (mode `exact`): G1 chains of biarcs within kExactCurveTolerance of the curve. The
//     pad's contact with an arc is solved in closed form, so the proxy's walk stays on the same
//     robust footing as for scene arcs, with force and l_d continuous along the curve (G1: no
//     spurious vertices); the proxy then re-solves the contacts it found on the exact curve.
//   * polyline (mode `flatten`): chords within a user tolerance (m); cheaper, with kinks at
//     every joint (small vertex pieces) and an error up to the tolerance.
// Degenerate control points (coincident, collinear with a reversal, a cubic's cusp) are handled by
// splitting the curve where its derivative vanishes: each piece has a well-defined tangent.
#pragma once

#include "haptics/vec2.hpp"

#include <array>
#include <vector>

namespace contactlab {

// A Bezier curve of degree 2 or 3 (control points in m); degree 2 uses p[0..2].
struct Bezier {
    int degree = 2;
    std::array<Vec2, 4> p{};
};

Vec2 bezier_point(const Bezier& b, double s);        // s in [0, 1]
Vec2 bezier_derivative(const Bezier& b, double s);   // dB/ds (m)
Vec2 bezier_second_derivative(const Bezier& b, double s);

// Parameters in (0, 1) where the derivative vanishes (cusps, reversals), ascending; at most 2.
int bezier_stationary_points(const Bezier& b, double out[2]);

// The parameter of the point of the curve nearest to q (exact for quadratics: roots of the cubic
// (B(s) - q) . B'(s) = 0; for cubics bracketed Newton over a fine partition), and its distance.
struct CurveFoot {
    double s = 0.0;
    double distance = 0.0;  // m
};
CurveFoot bezier_nearest(const Bezier& b, Vec2 q);

// A piece of a converted curve: a line or an arc (the scene's own segment types).
struct CurvePiece {
    bool is_arc = false;
    Vec2 from{0.0}, to{0.0};  // line
    Vec2 center{0.0};         // arc
    double radius = 0.0;
    double start_angle = 0.0, end_angle = 0.0;
    bool corner_after = false;  // the curve has a cusp or reversal where this piece ends
};

// Distance (m) within which the arc spline of exact mode follows the curve. The walk finds where
// the proxy rests on the arc spline; the proxy then re-solves its contacts on the true curve
// (proxy.cpp, refine_on_curves), so this only has to be fine enough to find the right place:
// 0.1 um keeps a 20 cm stimulus to a few hundred arcs (a finer spline costs time every tick).
inline constexpr double kExactCurveTolerance = 2e-8;

// Arc spline of the curve, G1 along each piece between stationary points, within `tolerance` (m).
void bezier_to_arcs(const Bezier& b, double tolerance, std::vector<CurvePiece>& out);
// Polyline of the curve with every chord within `tolerance` (m) of it.
void bezier_to_lines(const Bezier& b, double tolerance, std::vector<CurvePiece>& out);

// Largest distance (m) from the curve to the pieces, sampled densely (for tests and figures).
double curve_pieces_max_error(const Bezier& b, const std::vector<CurvePiece>& pieces, int samples = 4096);

}  // namespace contactlab
