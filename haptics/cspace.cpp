// cspace.cpp — building the c-space pieces of one segment for one finger angle, and the few
// geometric queries the proxy asks of a piece.
#include "haptics/cspace.hpp"

#include <algorithm>

namespace contactlab {
namespace {

// A pad end whose tangent makes less than this (cosine) with the contour is not a distinct
// contact: the pad's interior (an offset piece) already covers it.
constexpr double kEndpointCosTolerance = 1e-12;
// Where a line's contact passes from the pad's interior to its end (|R phi| = L/2 on a floor) both
// tests below sit on their threshold, and rounding can reject both: for that one angle the line
// had no piece at all and the proxy fell through the floor, never to come back (it was then
// behind every piece). Each test accepts this much (cosine) past its threshold, so near the
// transition both pieces exist. They coincide there; away from it the extra one lies inside the
// obstacle by about R (1 - cos(1e-12 / sin(L/2R))), far below 1e-20 m, so it never shows.
constexpr double kLineHandoverOverlap = 1e-12;
// m: an arc_inner piece of smaller radius than this is a point, not a curve to slide along.
constexpr double kMinInnerRadius = 1e-9;
// rad: inner vertex pieces of a needle's tip leave out this much of each side of its normal cone.
constexpr double kInnerConeMargin = 1e-6;

// The span of pad angles theta (rad) that can touch, for finger angle phi.
AngleSpan pad_span(const FingerShape& f, double phi) {
    const double h = pad_half_angle(f);
    if (h >= kPi) return {0.0, kTwoPi};
    return {wrap_2pi(pad_mid_angle(phi) - h), 2.0 * h};
}

// Direction in which the pad continues away from its end `k` (0: low-angle end, 1: high end).
Vec2 pad_inward_tangent(double theta_end, int k) {
    const Vec2 t = perp_left(unit_at(theta_end));
    return k == 0 ? t : -t;
}

// `base` is the caller's piece, its span overwritten: the callers set every field they push before
// each call, so taking it by value copied a whole piece per call for nothing (a fifth of a
// segment's build).
void push_circle(std::vector<CPiece>& out, CPiece& base, const AngleSpan& a, const AngleSpan& b) {
    AngleSpan parts[2];
    const int n = intersect_spans(a, b, parts);
    for (int i = 0; i < n; ++i) {
        base.span = parts[i];
        out.push_back(base);
    }
}

void append_vertex(int owner, Vec2 vertex, const AngleSpan& cone, const FingerShape& f, const AngleSpan& pads,
                   std::vector<CPiece>& out) {
    if (cone.width <= 0.0 || f.radius <= 0.0) return;
    CPiece p;
    p.kind = CPiece::Kind::circle;
    p.source = CPiece::Source::vertex;
    p.segment = owner;
    p.center = vertex;
    p.radius = f.radius;
    p.free_outside = true;
    // Centre at angle alpha about the vertex <=> the pad touches it at theta = alpha - pi, and the
    // contact normal (vertex toward centre) is u(alpha): it must lie in the vertex's normal cone.
    push_circle(out, p, cone, {wrap_2pi(pads.start + kPi), pads.width});
    if (!pad_has_endpoints(f)) return;
    // The concave side: both edges leave the vertex toward the centre, i.e. the pad's outward
    // direction u(theta) lies in the normal cone. Moving the vertex out of the pad's circle there
    // makes the edges cross the arc, so free space is inside.
    // At the tip of a needle (a contour doubling back on itself: cone width pi, both edges along
    // the pad's tangent at the cone's rim) the edges only graze the arc when the vertex leaves the
    // circle; the full cone made that tip a phantom wall for a pad sliding over a zero-thickness
    // overlap. Only there the rim's kInnerConeMargin is left out (an edge eps inside the rim cuts
    // the arc no deeper than eps^2 R / 2, ~1e-12 R). Elsewhere the rim must stay: it is where the
    // next curve's arc_inner piece takes over, and a gap there let the pad through.
    double lo = cone.start, width = cone.width;
    if (width >= kPi - kInnerConeMargin) {
        lo += kInnerConeMargin;
        width -= 2.0 * kInnerConeMargin;
    }
    p.source = CPiece::Source::vertex_inner;
    p.free_outside = false;
    push_circle(out, p, {wrap_2pi(lo + kPi), width}, {wrap_2pi(pads.start + kPi), pads.width});
}

void append_line(const EnvSegment& s, int index, const PadFrame& pad, std::vector<CPiece>& out) {
    const FingerShape& f = pad.finger;
    CPiece p;
    p.kind = CPiece::Kind::line;
    p.segment = index;
    p.dir = s.dir;
    p.len = s.length;
    p.n = s.normal;
    // Pad interior pressed by the line: the pad point facing -n must be on the pad, i.e. -n within
    // the pad's half-angle of its middle direction (a dot product: no atan2 per segment).
    if (glm::dot(-s.normal, pad.mid_dir) >= pad.cos_half - kLineHandoverOverlap) {
        p.source = CPiece::Source::line_offset;
        p.a = s.start + f.radius * s.normal;
        out.push_back(p);
    }
    if (!pad_has_endpoints(f)) return;
    for (int k = 0; k < 2; ++k) {
        if (glm::dot(pad.end_tangent[k], s.normal) <= -kLineHandoverOverlap) continue;
        p.source = CPiece::Source::endpoint;
        p.pad_theta = pad.end_theta[k];
        p.pad_l = pad.end_l[k];
        p.a = s.start - f.radius * pad.end_dir[k];
        out.push_back(p);
    }
}

void append_arc(const EnvSegment& s, int index, const PadFrame& pad, std::vector<CPiece>& out) {
    const FingerShape& f = pad.finger;
    const AngleSpan& pads = pad.span;
    CPiece p;
    p.kind = CPiece::Kind::circle;
    p.segment = index;
    p.contour_radius = s.radius;
    p.free_outside = s.free_outside;
    // Pad interior against the arc at contour angle beta: the contact normal is u(beta) on a bump
    // (pad angle beta + pi) and -u(beta) in a bowl (pad angle beta).
    p.source = CPiece::Source::arc_offset;
    p.center = s.center;
    if (s.free_outside) {
        p.radius = s.radius + f.radius;
        push_circle(out, p, s.angles, {wrap_2pi(pads.start - kPi), pads.width});
    } else if (s.radius > f.radius) {  // a bowl tighter than the pad only touches the pad's ends
        p.radius = s.radius - f.radius;
        push_circle(out, p, s.angles, pads);
    }
    if (!pad_has_endpoints(f)) return;
    // A bump tighter than the pad touching its concave side (cspace.hpp): the pad's circle holds
    // the bump's, tangent at contour angle beta = theta; the centre sits at beta + pi about the
    // bump's centre, R - rho from it. (At rho = R the piece shrinks to a point: skipped.)
    if (s.free_outside && s.radius < f.radius - kMinInnerRadius) {
        p.source = CPiece::Source::arc_inner;
        p.radius = f.radius - s.radius;
        p.free_outside = false;
        push_circle(out, p, {wrap_2pi(s.angles.start + kPi), s.angles.width}, {wrap_2pi(pads.start + kPi), pads.width});
        p.free_outside = s.free_outside;
    }
    for (int k = 0; k < 2; ++k) {
        p.source = CPiece::Source::endpoint;
        p.pad_theta = pad.end_theta[k];
        p.pad_l = pad.end_l[k];
        p.center = s.center - f.radius * pad.end_dir[k];
        p.radius = s.radius;
        // Non-penetrating where the pad leaves toward free space: tau . n(beta) > 0, a half circle
        // of beta centred on tau's direction (bump) or on -tau's (bowl).
        const double mid = s.free_outside ? pad.end_tangent_angle[k] : pad.end_tangent_angle[k] + kPi;
        const double half = 0.5 * kPi - kEndpointCosTolerance;
        push_circle(out, p, s.angles, {wrap_2pi(mid - half), 2.0 * half});
    }
}

}  // namespace

PadFrame make_pad_frame(const FingerShape& finger, double phi) {
    PadFrame pad;
    pad.finger = finger;
    pad.phi = phi;
    pad.span = pad_span(finger, phi);
    const double h = pad_half_angle(finger);
    pad.mid_dir = unit_at(pad_mid_angle(phi));
    pad.cos_half = h >= kPi ? -2.0 : std::cos(h);
    for (int k = 0; k < 2; ++k) {
        pad.end_theta[k] = pad_mid_angle(phi) + (k == 0 ? -h : h);
        pad.end_dir[k] = unit_at(pad.end_theta[k]);
        pad.end_tangent[k] = pad_inward_tangent(pad.end_theta[k], k);
        pad.end_tangent_angle[k] = angle_of(pad.end_tangent[k]);
        pad.end_l[k] = k == 0 ? -0.5 * finger.length : 0.5 * finger.length;
    }
    return pad;
}

void append_cspace_pieces(const Environment& env, int index, const PadFrame& pad, std::vector<CPiece>& out) {
    const EnvSegment& s = env.segments[index];
    if (s.kind == EnvSegment::Kind::line) {
        append_line(s, index, pad, out);
    } else {
        append_arc(s, index, pad, out);
    }
    append_vertex(index, s.end, s.end_cone, pad.finger, pad.span, out);
    append_vertex(index, s.start, s.start_cone, pad.finger, pad.span, out);
}

void append_cspace_pieces(const Environment& env, int index, const FingerShape& finger, double phi,
                          std::vector<CPiece>& out) {
    append_cspace_pieces(env, index, make_pad_frame(finger, phi), out);
}

double piece_signed_distance(const CPiece& piece, Vec2 p) {
    if (piece.kind == CPiece::Kind::line) return glm::dot(p - piece.a, piece.n);
    const double d = glm::length(p - piece.center) - piece.radius;
    return piece.free_outside ? d : -d;
}

Vec2 piece_normal_at(const CPiece& piece, Vec2 p) {
    if (piece.kind == CPiece::Kind::line) return piece.n;
    const Vec2 r = p - piece.center;
    const double len = glm::length(r);
    const Vec2 u = len > 0.0 ? r / len : Vec2(1.0, 0.0);
    return piece.free_outside ? u : -u;
}

double piece_param(const CPiece& piece, Vec2 p) {
    if (piece.kind == CPiece::Kind::line) return glm::dot(p - piece.a, piece.dir);
    const double rel = wrap_2pi(angle_of(p - piece.center) - piece.span.start);
    // Angles just before the span's start read as slightly negative, not as nearly 2 pi.
    return rel > 0.5 * (piece.span.width + kTwoPi) ? rel - kTwoPi : rel;
}

bool piece_param_inside(const CPiece& piece, double param, double slack) {
    const double hi = piece.kind == CPiece::Kind::line ? piece.len : piece.span.width;
    return param >= -slack && param <= hi + slack;
}

Vec2 piece_point(const CPiece& piece, double param) {
    if (piece.kind == CPiece::Kind::line) return piece.a + param * piece.dir;
    return piece.center + piece.radius * unit_at(piece.span.start + param);
}

PieceFoot piece_foot(const CPiece& piece, Vec2 p) {
    PieceFoot f;
    const double hi = piece.kind == CPiece::Kind::line ? piece.len : piece.span.width;
    if (piece.kind == CPiece::Kind::circle && glm::length(p - piece.center) == 0.0) {
        f.param = 0.5 * hi;  // every point is nearest: pick the middle, deterministically
    } else {
        f.param = piece_param(piece, p);
        if (piece.kind == CPiece::Kind::circle && f.param > hi) {
            // Outside the span: the nearer end by angle (rel in (hi, 2pi - ...)).
            f.param = (f.param - hi) <= (kTwoPi - f.param) ? hi : 0.0;
            f.clamped = true;
        }
    }
    if (f.param < 0.0) { f.param = 0.0; f.clamped = true; }
    if (f.param > hi) { f.param = hi; f.clamped = true; }
    f.point = piece_point(piece, f.param);
    return f;
}

Vec2 piece_contact_point(const CPiece& piece, const FingerShape& finger, Vec2 c) {
    switch (piece.source) {
        case CPiece::Source::line_offset: return c - finger.radius * piece.n;
        case CPiece::Source::vertex:
        case CPiece::Source::vertex_inner: return piece.center;
        case CPiece::Source::arc_inner: {
            // The contact lies beyond the bump's centre as seen from x_f.
            const Vec2 r = piece.center - c;
            const double len = glm::length(r);
            const Vec2 u = len > 0.0 ? r / len : Vec2(1.0, 0.0);
            return piece.center + piece.contour_radius * u;
        }
        case CPiece::Source::arc_offset: {
            const Vec2 r = c - piece.center;
            const double len = glm::length(r);
            const Vec2 u = len > 0.0 ? r / len : Vec2(1.0, 0.0);
            return piece.center + piece.contour_radius * u;
        }
        case CPiece::Source::endpoint: return c + finger.radius * unit_at(piece.pad_theta);
    }
    return c;
}

double piece_contact_location(const CPiece& piece, const FingerShape& finger, double phi, Vec2 c) {
    if (piece.source == CPiece::Source::endpoint) return piece.pad_l;
    if (finger.kind == FingerKind::point) return 0.0;
    // Direction from x_f to the contact, computed without subtracting nearly equal coordinates.
    double theta = 0.0;
    if (piece.source == CPiece::Source::line_offset) {
        theta = angle_of(-piece.n);
    } else if (piece.source == CPiece::Source::vertex || piece.source == CPiece::Source::vertex_inner ||
               piece.source == CPiece::Source::arc_inner) {
        theta = angle_of(piece.center - c);
    } else {  // arc_offset: x_f lies on the ray from the arc's centre through the contact
        const Vec2 r = c - piece.center;
        theta = angle_of(piece.free_outside ? -r : r);
    }
    const double l = contact_location_at(finger, phi, theta);
    // Numerically the angle can stray a hair past the pad's end: keep l on the pad.
    if (finger.kind == FingerKind::arc_pad) {
        return std::clamp(l, -0.5 * finger.length, 0.5 * finger.length);
    }
    return l;
}

Aabb piece_box(const CPiece& piece) {
    if (piece.kind == CPiece::Kind::line) {
        Aabb b;
        b.grow(piece.a);
        b.grow(piece.a + piece.len * piece.dir);
        return b;
    }
    return arc_bounds(piece.center, piece.radius, piece.span.start, piece.span.width);
}

}  // namespace contactlab
