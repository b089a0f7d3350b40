// vec2.hpp — the 2-D vector type of haptics/ and the few helpers every file needs.
// Units: metres for positions, radians for angles (DESIGN.md conventions).
#pragma once

#include <glm/vec2.hpp>
#include <glm/geometric.hpp>
#include <cmath>
#include <numbers>

namespace contactlab {

using Vec2 = glm::dvec2;

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

// z component of the 3-D cross product: > 0 when b is counter-clockwise from a.
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// a rotated by +90 degrees (counter-clockwise): the left normal of a direction.
inline Vec2 perp_left(Vec2 a) { return {-a.y, a.x}; }
// Unit vector at angle theta (rad, counter-clockwise from +x).
inline Vec2 unit_at(double theta) { return {std::cos(theta), std::sin(theta)}; }
inline double angle_of(Vec2 a) { return std::atan2(a.y, a.x); }
// Wraps an angle into (-pi, pi].
inline double wrap_pi(double a) {
    if (a > -kPi && a < kPi) return a;  // remainder returns these unchanged: skip it (same bits)
    a = std::remainder(a, kTwoPi);
    return a <= -kPi ? a + kTwoPi : a;
}
// Wraps an angle into [0, 2 pi).
inline double wrap_2pi(double a) {
    // Most angles are already in range or one turn below it: fmod returns those unchanged, so
    // skip it (the same bits; fmod was a tenth of a small scene's tick).
    if (a >= 0.0 && a < kTwoPi) return a;
    if (a < 0.0 && a > -kTwoPi) {
        a += kTwoPi;
        return a >= kTwoPi ? 0.0 : a;
    }
    // One turn above it (a pad's span turned by pi): a - 2 pi is exact there (Sterbenz: a within a
    // factor 2 of 2 pi), so it is fmod's answer, the same bits without the call (2 % of a dense
    // contour's tick, building vertex pieces).
    if (a >= kTwoPi && a < 2.0 * kTwoPi) return a - kTwoPi;
    a = std::fmod(a, kTwoPi);
    if (a < 0.0) a += kTwoPi;
    return a >= kTwoPi ? 0.0 : a;
}
inline bool is_finite(Vec2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }

}  // namespace contactlab
