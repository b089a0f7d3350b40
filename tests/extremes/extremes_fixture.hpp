// extremes_fixture.hpp — shared pieces of the extremes suite: the nominal values every extreme is
// a multiple of, scenes placed anywhere in the plane, and checks that an output is usable (finite,
// within the force clamp).
#pragma once

#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/scene.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <memory>

namespace contactlab::extremes {

// Nominal values (seed 000's device and finger); the suite scales them by 1e-6 and 1e6.
inline constexpr double kNominalStiffness = 1000.0;  // Ke, N/m
inline constexpr double kNominalMaxForce = 1.5;      // N
inline constexpr double kNominalRadius = 0.026;      // R, m
inline constexpr double kNominalLength = 0.020;      // L, m
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

// Tolerance (m) on a position computed from coordinates of magnitude `scale` (m): a few hundred
// units in the last place of the largest coordinate, and never below 1e-13 m. Every proxy result
// is a handful of arithmetic steps on such coordinates.
inline double position_tolerance(double scale) { return std::max(1e-13, 256.0 * kEps * std::abs(scale)); }

inline Segment line(Vec2 a, Vec2 b) { return LineSegment{a, b}; }

// A floor along y = origin.y from origin.x - half to origin.x + half (m), solid below.
inline Scene floor_at(Vec2 origin, double half = 0.3) {
    Scene s;
    Contour c;
    c.segments.push_back(line(origin + Vec2{-half, 0.0}, origin + Vec2{half, 0.0}));
    s.contours.push_back(c);
    return s;
}

// Seed 000's block (h = 6 cm, w = 10 cm) on a floor, all shifted by `origin` (m).
inline Scene block_at(Vec2 origin) {
    const Vec2 pts[] = {{-0.3, 0.0}, {-0.05, 0.0}, {-0.05, 0.06}, {0.05, 0.06}, {0.05, 0.0}, {0.3, 0.0}};
    Scene s;
    Contour c;
    for (int i = 0; i + 1 < 6; ++i) c.segments.push_back(line(origin + pts[i], origin + pts[i + 1]));
    s.contours.push_back(c);
    return s;
}

// A proxy with the environment it reads, kept alive together.
struct Rig {
    Environment env;
    std::unique_ptr<Proxy> proxy;
    Rig(const Scene& scene, const ProxyDef& def) : env(build_environment(scene)) {
        proxy = std::make_unique<Proxy>(env, def);
    }
    const ProxyOutput& at(Vec2 x, double phi, double dt = kDefaultServoPeriod) { return proxy->update(x, phi, dt); }
};

inline ProxyDef def_with(double radius, double length, double stiffness = kNominalStiffness,
                         double max_force = kNominalMaxForce) {
    ProxyDef d;
    d.finger = {FingerKind::arc_pad, radius, length};
    d.stiffness = stiffness;
    d.max_force = max_force;
    return d;
}

inline bool all_finite(const ProxyOutput& o) {
    bool ok = is_finite(o.finger) && std::isfinite(o.phi) && is_finite(o.proxy) && std::isfinite(o.depth) &&
              is_finite(o.force) && std::isfinite(o.l_d) && is_finite(o.anchor) &&
              is_finite(o.anticipated_point);
    for (int i = 0; i < o.contact_count; ++i) ok = ok && is_finite(o.contacts[i].point) && std::isfinite(o.contacts[i].l);
    return ok;
}

// The output is finite, its force within the clamp (N) to rounding, and the tick's work within
// the proxy's fixed bounds (so its cost is bounded whatever the input).
inline void check_usable(const ProxyOutput& o, double max_force) {
    REQUIRE(all_finite(o));
    CHECK(glm::length(o.force) <= max_force * (1.0 + 4.0 * kEps));
    CHECK(o.work.walk_steps >= 1);
    CHECK(o.work.walk_steps <= kProxyMaxWalkSteps);
    CHECK(o.work.rotation_steps <= kProxyMaxRotationSteps);
}

}  // namespace contactlab::extremes
