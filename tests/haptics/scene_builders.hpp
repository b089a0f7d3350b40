// scene_builders.hpp — small helpers for building scenes and running a proxy in tests.
#pragma once

#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/scene.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <memory>

namespace contactlab::test {

inline Segment line(Vec2 a, Vec2 b) { return LineSegment{a, b}; }
inline Segment arc(Vec2 c, double r, double a0, double a1) { return ArcSegment{c, r, a0, a1}; }

// An open chain through the given points (a polyline profile, solid on the right).
inline Contour polyline(std::initializer_list<Vec2> pts, bool closed = false) {
    Contour c;
    c.closed = closed;
    const Vec2* prev = nullptr;
    for (const Vec2& p : pts) {
        if (prev) c.segments.push_back(line(*prev, p));
        prev = &p;
    }
    if (closed) c.segments.push_back(line(*prev, *pts.begin()));
    return c;
}

// A sinusoid over x in [-0.2, 0.2] m (the bench's 0.4 m dense contour) cut into n chords:
// y = amplitude sin(2 pi periods (x + 0.2) / 0.4), solid below.
inline Contour sinusoid_contour(int n, double amplitude, double periods) {
    Contour c;
    auto at = [&](int i) {
        const double x = -0.2 + 0.4 * i / n;  // m
        return Vec2{x, amplitude * std::sin(2.0 * kPi * periods * (x + 0.2) / 0.4)};
    };
    for (int i = 0; i < n; ++i) c.segments.push_back(line(at(i), at(i + 1)));
    return c;
}

inline Scene scene_of(std::initializer_list<Contour> contours) {
    Scene s;
    s.contours = contours;
    return s;
}

// A proxy together with the environment it reads (kept alive together).
struct ProxyRig {
    Environment env;
    std::unique_ptr<Proxy> proxy;
    explicit ProxyRig(const Scene& scene) : env(build_environment(scene)) {
        proxy = std::make_unique<Proxy>(env, proxy_def_of(scene));
    }
    ProxyRig(const Scene& scene, const FingerShape& finger) : env(build_environment(scene)) {
        ProxyDef def = proxy_def_of(scene);
        def.finger = finger;
        proxy = std::make_unique<Proxy>(env, def);
    }
    const ProxyOutput& at(Vec2 x, double phi) { return proxy->update(x, phi); }
};

// The block scene of seed 000 as used in tests: floor, a block of height h and width w centred at
// x = 0, floor again.
inline Scene block_scene(double h = 0.06, double w = 0.10) {
    return scene_of({polyline({{-0.3, 0.0}, {-w / 2, 0.0}, {-w / 2, h}, {w / 2, h}, {w / 2, 0.0},
                               {0.3, 0.0}})});
}

}  // namespace contactlab::test

// Prints Vec2 in doctest messages as (x, y) with full precision.
namespace doctest {
template <> struct StringMaker<contactlab::Vec2> {
    static String convert(const contactlab::Vec2& v) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", v.x, v.y);
        return buf;
    }
};
}  // namespace doctest
