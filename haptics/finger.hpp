// finger.hpp — the finger models behind one interface: point, full circle, arc pad (seed 000).
//
// Every model is described by the same few numbers so the c-space code has one path:
//   * the pad circle's radius R (0 for the point finger),
//   * the span of pad angles theta (rad) that can touch, relative to the finger angle phi,
//   * whether the span has endpoints (the arc pad's two ends) or is the whole circle.
// Contact location l (m) is arc length from the pad's midpoint, positive toward the fingertip.
#pragma once

#include "haptics/scene.hpp"
#include "haptics/vec2.hpp"

namespace contactlab {

enum class FingerKind {
    point,        // x_f itself touches; l is always 0
    full_circle,  // a disc of radius R (a spherical proxy in 2-D); l measured round the whole circle
    arc_pad,      // seed 000's fingerpad: arc of radius R and length L
};

struct FingerShape {
    FingerKind kind = FingerKind::arc_pad;
    double radius = 0.026;  // R, m
    double length = 0.020;  // L, m (arc_pad only)
    bool operator==(const FingerShape&) const = default;
};

inline FingerShape finger_from_def(const FingerDef& d) {
    return {FingerKind::arc_pad, d.radius, d.length};
}

// Half the angular width of the pad (rad): L / (2R) for the pad, pi for the full circle.
inline double pad_half_angle(const FingerShape& f) {
    switch (f.kind) {
        case FingerKind::point: return kPi;
        case FingerKind::full_circle: return kPi;
        case FingerKind::arc_pad: return 0.5 * f.length / f.radius;
    }
    return 0.0;
}
inline bool pad_has_endpoints(const FingerShape& f) { return f.kind == FingerKind::arc_pad; }
// Angle (rad) of the pad's midpoint as seen from x_f: the pad faces phi - pi/2.
inline double pad_mid_angle(double phi) { return phi - 0.5 * kPi; }
// Contact location (m) of the pad point at angle theta (rad) for finger angle phi.
inline double contact_location_at(const FingerShape& f, double phi, double theta) {
    if (f.kind == FingerKind::point) return 0.0;
    return f.radius * wrap_pi(theta - pad_mid_angle(phi));
}

}  // namespace contactlab
