// finger_state.cpp — settle the proxy for a still picture (see finger_state.hpp).
#include "engine/render/finger_state.hpp"

#include <algorithm>
#include <limits>

namespace contactlab::render {
namespace {

// Nearest point on segment s to p (m).
Vec2 nearest_point(const EnvSegment& s, Vec2 p) {
    if (s.kind == EnvSegment::Kind::line) {
        const double t = std::clamp(glm::dot(p - s.start, s.dir), 0.0, s.length);
        return s.start + t * s.dir;
    }
    const double a = angle_of(p - s.center);
    if (span_contains(s.angles, a)) return s.center + s.radius * unit_at(a);
    return glm::length(p - s.start) < glm::length(p - s.end) ? s.start : s.end;
}

// Index of the segment nearest to p, and its distance (m); -1 when the scene is empty.
int nearest_segment(const Environment& env, Vec2 p, double& distance) {
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    distance = env.tree.nearest_distance(p, [&](int i) {
        const double d = distance_to_segment(env.segments[i], p);
        if (d < best_d || (d == best_d && i < best)) { best_d = d; best = i; }
        return d;
    });
    return best;
}

}  // namespace

Vec2 approach_start(const Environment& env, const ProxyDef& def, Vec2 finger) {
    const double R = def.finger.radius;
    const Vec2 fallback = finger + Vec2(0.0, 0.1);
    if (env.segments.empty()) return finger;
    double d = 0.0;
    const int i = nearest_segment(env, finger, d);
    if (i < 0) return fallback;
    const EnvSegment& s = env.segments[i];
    const Vec2 q = nearest_point(s, finger);
    Vec2 n = env_normal_at(s, q);
    // At an open chain's end or a convex corner the direction away from the contour is better.
    if (glm::length(finger - q) > 1e-12 && glm::dot(finger - q, n) > 0.0) n = glm::normalize(finger - q);
    for (double k : {1.5, 3.0, 6.0, 12.0, 24.0}) {
        const Vec2 start = q + n * (k * R);
        double clearance = 0.0;
        nearest_segment(env, start, clearance);
        if (clearance >= 1.05 * R) return start;
    }
    return fallback;
}

ProxyOutput settle_proxy(const Environment& env, const ProxyDef& def, FingerPose pose) {
    Proxy proxy(env, def);
    proxy.reset(approach_start(env, def, pose.center), pose.phi);
    return proxy.update(pose.center, pose.phi);
}

FingerPose default_finger_pose(const Environment& env, const ProxyDef& def) {
    if (env.segments.empty()) return {};
    const Vec2 c = env.bounds.center();
    return {{c.x, env.bounds.hi.y + def.finger.radius - 0.001}, 0.0};
}

}  // namespace contactlab::render
