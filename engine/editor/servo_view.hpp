// servo_view.hpp — what the frame draws for the finger, from the servo's lock-free snapshot: the
// proxy output the drawer expects (finger, proxy, force, l_d, one contact site), and the servo
// parameters the editor publishes (Ke and max force from the scene, roller gains from the panel).
#pragma once

#include "haptics/proxy.hpp"
#include "haptics/scene.hpp"
#include "haptics/servo_tick.hpp"

namespace contactlab::editor {

// The snapshot carries no contact list: in contact, the site drawn is the proxy pad's point at
// l_d (exact for one contact; the centroid's pad point for several).
ProxyOutput proxy_output_from(const ServoSnapshot& snap, const FingerDef& finger);

// The mouse moves no motor, so a stalled tick cannot kick anyone: its watchdog allows 50 ms
// (kMouseWatchdog) instead of 5 ms. Under Xvfb + lavapipe on two cores the servo thread, even at
// SCHED_FIFO, sees gaps of 10-15 ms (Xvfb's kernel copies of each frame hold its CPU); with the
// 5 ms default every such gap would fault and drop the force until the finger left contact.
inline constexpr double kMouseWatchdog = 0.050;  // s
// roller_travel (m): the usable roller travel (ServoParams::roller_travel; 0: the device's whole).
ServoParams servo_params_for(const Scene& scene, const RollerGains& roller, double watchdog_timeout,
                             double roller_travel = 0.0);
bool same_params(const ServoParams& a, const ServoParams& b);

}  // namespace contactlab::editor
