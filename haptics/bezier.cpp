// bezier.cpp — Bezier evaluation, nearest point, stationary points, arc-spline and polyline
// conversion (see bezier.hpp).
//
// Index
//   [SECTION] Evaluation
//   [SECTION] Stationary points       where B'(s) = 0: cusps and reversals split the curve
//   [SECTION] Nearest point           cubic roots (quadratic curves), bracketed Newton (cubic)
//   [SECTION] Pieces                  distance from a point to a line/arc piece
//   [SECTION] Arc spline              recursive biarc fitting
//   [SECTION] Polyline                recursive chord fitting
#include "haptics/bezier.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contactlab {
namespace {

// Subdivision depth limit: 2^-40 of the parameter range is below double resolution of any curve
// a scene can hold, so the limit only guards against pathological input.
constexpr int kMaxDepth = 40;
// Samples per piece when checking a fit against the curve.
constexpr int kFitSamples = 9;

double curve_scale(const Bezier& b) {
    double s = 0.0;
    for (int i = 0; i < b.degree; ++i) s = std::max(s, glm::length(b.p[i + 1] - b.p[i]));
    return s;
}

}  // namespace

//-------------------------------------------------------------------------------------------------
// [SECTION] Evaluation
//-------------------------------------------------------------------------------------------------

Vec2 bezier_point(const Bezier& b, double s) {
    const double t = 1.0 - s;
    if (b.degree == 2) return t * t * b.p[0] + 2.0 * t * s * b.p[1] + s * s * b.p[2];
    return t * t * t * b.p[0] + 3.0 * t * t * s * b.p[1] + 3.0 * t * s * s * b.p[2] + s * s * s * b.p[3];
}

Vec2 bezier_derivative(const Bezier& b, double s) {
    const double t = 1.0 - s;
    if (b.degree == 2) return 2.0 * (t * (b.p[1] - b.p[0]) + s * (b.p[2] - b.p[1]));
    return 3.0 * (t * t * (b.p[1] - b.p[0]) + 2.0 * t * s * (b.p[2] - b.p[1]) + s * s * (b.p[3] - b.p[2]));
}

Vec2 bezier_second_derivative(const Bezier& b, double s) {
    if (b.degree == 2) return 2.0 * (b.p[2] - 2.0 * b.p[1] + b.p[0]);
    return 6.0 * ((1.0 - s) * (b.p[2] - 2.0 * b.p[1] + b.p[0]) + s * (b.p[3] - 2.0 * b.p[2] + b.p[1]));
}

//-------------------------------------------------------------------------------------------------
// [SECTION] Stationary points
//-------------------------------------------------------------------------------------------------

// |B'(s)|^2 is a polynomial of degree 2 (quadratic curve) or 4 (cubic). Its zeros are its minima
// with value 0: scan for local minima, refine each by golden-section search, and keep those where
// |B'| is negligible against the curve's size.
int bezier_stationary_points(const Bezier& b, double out[2]) {
    const double scale = curve_scale(b);
    if (scale <= 0.0) return 0;
    if (b.degree == 2) {
        // A quadratic's speed is 2 |(1 - s) u + s v| with legs u, v; with u.v > 0 its square is at
        // least (1 - s)^2 |u|^2 + s^2 |v|^2 >= |u|^2 |v|^2 / (|u|^2 + |v|^2), so the speed is at
        // least sqrt(2) min(|u|, |v|) everywhere. Legs longer than 1e-6 of the scale then keep
        // it a thousand times above the 1e-9 of the scale the scan below accepts, whatever the
        // roundings: no stationary point, found without the scan (an eighth of a seed 002
        // scene's curves' time).
        const Vec2 u = b.p[1] - b.p[0], v = b.p[2] - b.p[1];
        if (glm::dot(u, v) > 0.0 && std::min(glm::length(u), glm::length(v)) > 1e-6 * scale) return 0;
    }
    auto speed = [&](double s) { return glm::length(bezier_derivative(b, s)); };
    constexpr int kScan = 64;
    int count = 0;
    double prev2 = speed(0.0), prev1 = speed(1.0 / kScan);
    for (int i = 2; i <= kScan && count < 2; ++i) {
        const double cur = speed(static_cast<double>(i) / kScan);
        if (prev1 <= prev2 && prev1 <= cur) {
            double lo = static_cast<double>(i - 2) / kScan, hi = static_cast<double>(i) / kScan;
            const double g = 0.5 * (std::sqrt(5.0) - 1.0);
            for (int k = 0; k < 80; ++k) {
                const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
                if (speed(m1) < speed(m2)) hi = m2; else lo = m1;
            }
            const double s = 0.5 * (lo + hi);
            const bool interior = s > 1e-9 && s < 1.0 - 1e-9;
            const bool fresh = count == 0 || s - out[count - 1] > 1e-9;
            if (interior && fresh && speed(s) <= 1e-9 * scale) out[count++] = s;
        }
        prev2 = prev1;
        prev1 = cur;
    }
    return count;
}

//-------------------------------------------------------------------------------------------------
// [SECTION] Nearest point
//-------------------------------------------------------------------------------------------------
namespace {

// Real roots of c3 s^3 + c2 s^2 + c1 s + c0 (any coefficients may vanish), polished by Newton.
int solve_cubic(double c3, double c2, double c1, double c0, double roots[3]) {
    const double big = std::max({std::abs(c3), std::abs(c2), std::abs(c1), std::abs(c0)});
    if (big == 0.0) return 0;
    int n = 0;
    if (std::abs(c3) <= 1e-14 * big) {  // quadratic (or lower)
        if (std::abs(c2) <= 1e-14 * big) {
            if (std::abs(c1) <= 1e-14 * big) return 0;
            roots[n++] = -c0 / c1;
        } else {
            const double disc = c1 * c1 - 4.0 * c2 * c0;
            if (disc < 0.0) return 0;
            const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
            roots[n++] = q / c2;
            if (q != 0.0) roots[n++] = c0 / q;
        }
    } else {
        // Depressed cubic t^3 + p t + q = 0 with s = t - a/3 (trigonometric or Cardano form).
        const double a = c2 / c3, bb = c1 / c3, c = c0 / c3;
        const double p = bb - a * a / 3.0;
        const double q = 2.0 * a * a * a / 27.0 - a * bb / 3.0 + c;
        const double disc = q * q / 4.0 + p * p * p / 27.0;
        if (disc > 0.0) {
            const double sq = std::sqrt(disc);
            roots[n++] = std::cbrt(-q / 2.0 + sq) + std::cbrt(-q / 2.0 - sq) - a / 3.0;
        } else if (p == 0.0) {
            roots[n++] = -a / 3.0;
        } else {
            const double r = std::sqrt(-p / 3.0);
            const double phi = std::acos(std::clamp(-q / (2.0 * r * r * r), -1.0, 1.0));
            for (int k = 0; k < 3; ++k) roots[n++] = 2.0 * r * std::cos((phi - kTwoPi * k) / 3.0) - a / 3.0;
        }
    }
    for (int i = 0; i < n; ++i) {  // Newton polish: the closed forms lose digits near double roots
        double s = roots[i];
        for (int k = 0; k < 3; ++k) {
            const double f = ((c3 * s + c2) * s + c1) * s + c0;
            const double df = (3.0 * c3 * s + 2.0 * c2) * s + c1;
            if (df == 0.0) break;
            const double next = s - f / df;
            if (!std::isfinite(next)) break;
            s = next;
        }
        roots[i] = s;
    }
    return n;
}

// (B(s) - q) . B'(s): zero at every foot of q on the curve.
double foot_function(const Bezier& b, Vec2 q, double s) {
    return glm::dot(bezier_point(b, s) - q, bezier_derivative(b, s));
}

}  // namespace

CurveFoot bezier_nearest(const Bezier& b, Vec2 q) {
    CurveFoot best{0.0, glm::length(bezier_point(b, 0.0) - q)};
    auto consider = [&](double s) {
        if (!std::isfinite(s)) return;
        s = std::clamp(s, 0.0, 1.0);
        const double d = glm::length(bezier_point(b, s) - q);
        if (d < best.distance) best = {s, d};
    };
    consider(1.0);
    if (b.degree == 2) {
        // B(s) = p0 + 2 s a + s^2 c with a = p1 - p0, c = p2 - 2 p1 + p0, and m = p0 - q:
        // (B - q) . B' / 2 = (c.c) s^3 + 3 (a.c) s^2 + (2 a.a + m.c) s + m.a.
        const Vec2 a = b.p[1] - b.p[0], c = b.p[2] - 2.0 * b.p[1] + b.p[0], m = b.p[0] - q;
        double roots[3];
        const int n = solve_cubic(glm::dot(c, c), 3.0 * glm::dot(a, c), 2.0 * glm::dot(a, a) + glm::dot(m, c),
                                  glm::dot(m, a), roots);
        for (int i = 0; i < n; ++i) consider(roots[i]);
        return best;
    }
    // Cubic: the foot function is a quintic; bracket its sign changes on a fine partition, then
    // Newton safeguarded by bisection inside each bracket.
    constexpr int kParts = 64;
    double s_prev = 0.0, f_prev = foot_function(b, q, 0.0);
    for (int i = 1; i <= kParts; ++i) {
        const double s_cur = static_cast<double>(i) / kParts;
        const double f_cur = foot_function(b, q, s_cur);
        if ((f_prev <= 0.0) != (f_cur <= 0.0)) {
            double lo = s_prev, hi = s_cur, f_lo = f_prev;
            double s = 0.5 * (lo + hi);
            for (int k = 0; k < 60; ++k) {
                const double f = foot_function(b, q, s);
                if ((f <= 0.0) == (f_lo <= 0.0)) { lo = s; f_lo = f; } else { hi = s; }
                const Vec2 d1 = bezier_derivative(b, s);
                const double df = glm::dot(d1, d1) + glm::dot(bezier_point(b, s) - q, bezier_second_derivative(b, s));
                double next = df != 0.0 ? s - f / df : 0.5 * (lo + hi);
                if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
                if (std::abs(next - s) <= 1e-16) { s = next; break; }
                s = next;
            }
            consider(s);
        }
        s_prev = s_cur;
        f_prev = f_cur;
    }
    return best;
}

//-------------------------------------------------------------------------------------------------
// [SECTION] Pieces
//-------------------------------------------------------------------------------------------------
namespace {

double distance_to_piece(const CurvePiece& piece, Vec2 q) {
    if (!piece.is_arc) {
        const Vec2 d = piece.to - piece.from;
        const double len2 = glm::dot(d, d);
        const double t = len2 > 0.0 ? std::clamp(glm::dot(q - piece.from, d) / len2, 0.0, 1.0) : 0.0;
        return glm::length(piece.from + t * d - q);
    }
    const double lo = std::min(piece.start_angle, piece.end_angle);
    const double width = std::abs(piece.end_angle - piece.start_angle);
    const double rel = wrap_2pi(angle_of(q - piece.center) - lo);
    if (rel <= width) return std::abs(glm::length(q - piece.center) - piece.radius);
    const Vec2 a = piece.center + piece.radius * unit_at(piece.start_angle);
    const Vec2 e = piece.center + piece.radius * unit_at(piece.end_angle);
    return std::min(glm::length(q - a), glm::length(q - e));
}

// Unit tangent (direction of travel) at s; where the derivative vanishes (a cusp or a
// coincident control point) the limit of the derivative's direction from the side of s_other.
Vec2 tangent_toward(const Bezier& b, double s, double s_other, double scale) {
    Vec2 d = bezier_derivative(b, s);
    if (glm::length(d) <= 1e-12 * scale) {
        const double step = (s_other - s) * 1e-6;
        d = bezier_derivative(b, s + step);
        if (glm::length(d) <= 0.0) d = bezier_point(b, s_other) - bezier_point(b, s);
    }
    return glm::normalize(d);
}

// The arc (or line, when the arc would be flatter than 1e-13 m) leaving P along unit tangent T
// and ending at Q.
CurvePiece arc_through(Vec2 P, Vec2 T, Vec2 Q) {
    CurvePiece piece;
    piece.from = P;
    piece.to = Q;
    const Vec2 c = Q - P;
    const double c2 = glm::dot(c, c);
    const double k = 2.0 * cross(T, c) / c2;  // signed curvature, 1/m (> 0: turning left)
    if (std::abs(k) * c2 / 8.0 < 1e-13) return piece;  // sagitta below 1e-13 m: a line
    piece.is_arc = true;
    piece.center = P + perp_left(T) / k;
    piece.radius = 1.0 / std::abs(k);
    const double a0 = angle_of(P - piece.center), a1 = angle_of(Q - piece.center);
    piece.start_angle = a0;
    piece.end_angle = k > 0.0 ? a0 + wrap_2pi(a1 - a0) : a0 - wrap_2pi(a0 - a1);
    return piece;
}

// Whether the pieces lie within `tol` (m) of the curve over [s0, s1] at the check samples: every
// sample within tol of its nearest piece. The fit's worst distance is not needed, only this
// answer: the samples stop at the first one beyond tol, and a sample already within tol of a
// piece asks no other (a third of building a seed 002 scene went to these distances).
bool fits_within(const Bezier& b, double s0, double s1, const CurvePiece* pieces, int count, double tol) {
    for (int i = 1; i <= kFitSamples; ++i) {
        const Vec2 q = bezier_point(b, s0 + (s1 - s0) * i / (kFitSamples + 1.0));
        bool near = false;
        for (int k = 0; k < count && !near; ++k) near = distance_to_piece(pieces[k], q) <= tol;
        if (!near && count > 0) return false;
    }
    return true;
}

//-------------------------------------------------------------------------------------------------
// [SECTION] Arc spline
//-------------------------------------------------------------------------------------------------

// A biarc from P0 (tangent T0) to P1 (tangent T1): two arcs meeting G1 at a joint chosen with
// equal tangent lengths d (the classic "equal-d" biarc).
int biarc(Vec2 P0, Vec2 T0, Vec2 P1, Vec2 T1, CurvePiece out[2]) {
    const Vec2 v = P1 - P0;
    const Vec2 t = T0 + T1;
    const double denom = 2.0 * (1.0 - glm::dot(T0, T1));
    double d;
    if (denom < 1e-12) {
        const double vt = glm::dot(v, T1);
        if (std::abs(vt) <= 1e-300) { out[0] = arc_through(P0, T0, P1); return 1; }
        d = glm::dot(v, v) / (4.0 * vt);
    } else {
        // Positive root of denom d^2 + 2 (v.t) d - v.v = 0, in the form without cancellation: for
        // nearly parallel tangents denom -> 0 and the textbook form loses every digit.
        const double vt = glm::dot(v, t);
        const double root = std::sqrt(vt * vt + denom * glm::dot(v, v));
        d = vt >= 0.0 ? glm::dot(v, v) / (vt + root) : (root - vt) / denom;
    }
    const Vec2 joint = 0.5 * (P0 + P1 + d * (T0 - T1));
    if (glm::length(joint - P0) <= 0.0 || glm::length(P1 - joint) <= 0.0) {
        out[0] = arc_through(P0, T0, P1);
        return 1;
    }
    out[0] = arc_through(P0, T0, joint);
    // The second arc, built backwards from P1 along -T1, then reversed to run joint -> P1.
    CurvePiece back = arc_through(P1, -T1, joint);
    std::swap(back.from, back.to);
    std::swap(back.start_angle, back.end_angle);
    out[1] = back;
    return 2;
}

void arcs_between(const Bezier& b, double s0, double s1, double tol, double scale, int depth,
                  std::vector<CurvePiece>& out) {
    const Vec2 P0 = bezier_point(b, s0), P1 = bezier_point(b, s1);
    if (glm::length(P1 - P0) <= 0.0) return;
    CurvePiece pieces[2];
    const int n = biarc(P0, tangent_toward(b, s0, s1, scale), P1, tangent_toward(b, s1, s0, scale), pieces);
    if (depth >= kMaxDepth || fits_within(b, s0, s1, pieces, n, tol)) {
        for (int i = 0; i < n; ++i) out.push_back(pieces[i]);
        return;
    }
    const double mid = 0.5 * (s0 + s1);
    arcs_between(b, s0, mid, tol, scale, depth + 1, out);
    arcs_between(b, mid, s1, tol, scale, depth + 1, out);
}

//-------------------------------------------------------------------------------------------------
// [SECTION] Polyline
//-------------------------------------------------------------------------------------------------

void lines_between(const Bezier& b, double s0, double s1, double tol, int depth, std::vector<CurvePiece>& out) {
    CurvePiece chord;
    chord.from = bezier_point(b, s0);
    chord.to = bezier_point(b, s1);
    if (depth >= kMaxDepth || fits_within(b, s0, s1, &chord, 1, tol)) {
        if (glm::length(chord.to - chord.from) > 0.0) out.push_back(chord);
        return;
    }
    const double mid = 0.5 * (s0 + s1);
    lines_between(b, s0, mid, tol, depth + 1, out);
    lines_between(b, mid, s1, tol, depth + 1, out);
}

// Splits [0, 1] at the stationary points and calls fit(s0, s1) on each part.
template <class Fit>
void for_each_regular_part(const Bezier& b, Fit fit) {
    double cuts[2];
    const int n = bezier_stationary_points(b, cuts);
    double s0 = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double s1 = i < n ? cuts[i] : 1.0;
        fit(s0, s1, i < n);
        s0 = s1;
    }
}

}  // namespace

void bezier_to_arcs(const Bezier& b, double tolerance, std::vector<CurvePiece>& out) {
    const double scale = curve_scale(b);
    const std::size_t first = out.size();
    for_each_regular_part(b, [&](double s0, double s1, bool corner) {
        const std::size_t before = out.size();
        arcs_between(b, s0, s1, tolerance, scale, 0, out);
        if (corner && out.size() > before) out.back().corner_after = true;
    });
    // Join exactly: each piece starts where the previous one ended (bit-for-bit), and the chain
    // starts and ends at the curve's own end points.
    for (std::size_t i = first; i < out.size(); ++i) {
        if (i > first) out[i].from = out[i - 1].to;
    }
    if (out.size() > first) {
        out[first].from = b.p[0];
        out.back().to = b.p[b.degree];
    }
}

void bezier_to_lines(const Bezier& b, double tolerance, std::vector<CurvePiece>& out) {
    const std::size_t first = out.size();
    for_each_regular_part(b, [&](double s0, double s1, bool corner) {
        const std::size_t before = out.size();
        lines_between(b, s0, s1, tolerance, 0, out);
        if (corner && out.size() > before) out.back().corner_after = true;
    });
    for (std::size_t i = first + 1; i < out.size(); ++i) out[i].from = out[i - 1].to;
    if (out.size() > first) {
        out[first].from = b.p[0];
        out.back().to = b.p[b.degree];
    }
}

double curve_pieces_max_error(const Bezier& b, const std::vector<CurvePiece>& pieces, int samples) {
    double worst = 0.0;
    for (int i = 0; i <= samples; ++i) {
        const Vec2 q = bezier_point(b, static_cast<double>(i) / samples);
        double d = std::numeric_limits<double>::infinity();
        for (const CurvePiece& p : pieces) d = std::min(d, distance_to_piece(p, q));
        worst = std::max(worst, d);
    }
    return worst;
}

}  // namespace contactlab
