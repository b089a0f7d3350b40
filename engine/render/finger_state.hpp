// finger_state.hpp — the proxy state a still picture shows: what the haptics Proxy computes for a
// finger configuration reached from free space (the user's finger came down onto the surface).
#pragma once

#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/scene.hpp"

namespace contactlab::render {

struct FingerPose {
    Vec2 center{0.0};  // x_f, m
    double phi = 0.0;  // rad
};

// (The proxy definition of a scene is haptics' proxy_def_of, proxy.hpp.)

// A free-space start for the approach: from the contour point nearest the finger, out along the
// contour's free-side normal until a disc of radius 1.05 R there touches nothing. Falls back to
// 0.1 m straight above the finger.
Vec2 approach_start(const Environment& env, const ProxyDef& def, Vec2 finger);

// Resets a proxy at approach_start and updates it once to the finger: the swept god-object stops
// on the surface the finger pressed into.
ProxyOutput settle_proxy(const Environment& env, const ProxyDef& def, FingerPose pose);

// The pose `contactlab render` uses without --finger: above the middle of the scene, the pad's
// lowest point 1 mm below the top of the scene's bounds, phi = 0.
FingerPose default_finger_pose(const Environment& env, const ProxyDef& def);

}  // namespace contactlab::render
