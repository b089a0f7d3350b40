// servo_view.cpp — snapshot -> drawable proxy state; scene -> servo parameters.
#include "engine/editor/servo_view.hpp"

#include "haptics/finger.hpp"

namespace contactlab::editor {

ProxyOutput proxy_output_from(const ServoSnapshot& snap, const FingerDef& finger) {
    ProxyOutput o;
    o.finger = snap.finger;
    o.phi = snap.phi;
    o.proxy = snap.contact ? snap.proxy : snap.finger;
    o.contact = snap.contact;
    o.depth = snap.depth;
    o.force = snap.force;  // N, as commanded after safety (zero while stopped or faulted)
    o.l_d = snap.l_d;
    o.anchor = o.proxy;
    if (snap.contact) {
        o.contact_count = 1;
        o.contacts[0].l = snap.l_d;
        o.contacts[0].point = o.proxy + finger.radius * unit_at(pad_mid_angle(snap.phi) + snap.l_d / finger.radius);
    }
    return o;
}

ServoParams servo_params_for(const Scene& scene, const RollerGains& roller, double watchdog_timeout,
                             double roller_travel) {
    ServoParams p;
    p.roller_travel = roller_travel;  // m
    p.safety.watchdog_timeout = watchdog_timeout;  // s
    p.stiffness = scene.force.stiffness;  // N/m
    p.max_force = scene.force.max_force;  // N
    p.passivity = scene.force.passivity;
    p.roller = roller;
    return p;
}

bool same_params(const ServoParams& a, const ServoParams& b) {
    return a.stiffness == b.stiffness && a.max_force == b.max_force && a.passivity == b.passivity &&
           a.roller.kp == b.roller.kp &&
           a.roller.ki == b.roller.ki && a.roller.kd == b.roller.kd && a.roller.max_drive == b.roller.max_drive &&
           a.roller.d_cutoff_hz == b.roller.d_cutoff_hz && a.roller.kff == b.roller.kff &&
           a.roller.ff_cutoff_hz == b.roller.ff_cutoff_hz &&
           a.roller.pole == b.roller.pole && a.roller.max_pole_period == b.roller.max_pole_period &&
           a.roller.back_emf == b.roller.back_emf &&
           a.safety.watchdog_timeout == b.safety.watchdog_timeout && a.roller_travel == b.roller_travel;
}

}  // namespace contactlab::editor
