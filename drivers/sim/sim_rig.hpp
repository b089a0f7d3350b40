// sim_rig.hpp — the servo loop against the simulated CLD rig (arm + roller + scripted hand) in
// virtual time: what the measurement probes (drivers/sim/bench_probes.hpp) and the tests drive.
// One definition, so a probe's table and a test's assertion are about the same closed loop.
#pragma once

#include "drivers/hand_path.hpp"
#include "drivers/servo_loop.hpp"
#include "drivers/sim/sim_cld_device.hpp"
#include "haptics/scene.hpp"
#include "haptics/servo_tick.hpp"

#include <algorithm>
#include <memory>
#include <utility>

namespace contactlab::drivers::sim {

// A flat floor along y = 0 from x = -1 m to 1 m (solid below); `stiffness` in N/m.
inline Scene floor_scene(double stiffness = 1000.0) {
    Scene s;
    Contour c;
    c.segments.push_back(LineSegment{{-1.0, 0.0}, {1.0, 0.0}});
    s.contours.push_back(c);
    s.force.stiffness = stiffness;
    return s;
}

// Device, servo tick and loop wired together at `rate` (Hz), the scene published, the device
// opened (`opened` says whether it was). Step it with loop.step(1 / rate, true).
struct SimRig {
    SimRig(const Scene& scene, HandPath path, double rate = 1000.0, const SimCldParams& sp = {},
           ServoParams params = default_params())
        : device(with_watchdog(sp, rate), std::move(path)),
          servo(servo_config_for(device, rate), with_watchdog(with_scene(params, scene), rate)),
          loop(device, servo, 1.0 / rate) {
        servo.scenes().publish(std::make_unique<ServoScene>(scene));
        opened = loop.start();
    }
    SimRig(const SimRig&) = delete;  // the loop holds references to device and servo
    SimRig& operator=(const SimRig&) = delete;
    static ServoParams default_params() { return ServoParams{}; }
    // A stall watchdog (servo's and the simulated amplifiers') shorter than a few periods trips on
    // every tick at low rates: at least 3 periods (s), as `contactlab simulate` sets it.
    static double watchdog_for(double rate) { return 3.0 / rate; }
    static SimCldParams with_watchdog(SimCldParams sp, double rate) {
        sp.watchdog_timeout = std::max(sp.watchdog_timeout, watchdog_for(rate));
        return sp;
    }
    static ServoParams with_watchdog(ServoParams p, double rate) {
        p.safety.watchdog_timeout = std::max(p.safety.watchdog_timeout, watchdog_for(rate));
        return p;
    }
    // The scene's own stiffness (N/m) and force limit (N) win over `p`'s.
    static ServoParams with_scene(ServoParams p, const Scene& s) {
        p.stiffness = s.force.stiffness;
        p.max_force = s.force.max_force;
        return p;
    }
    SimCldDevice device;
    ServoTick servo;
    ServoLoop loop;
    bool opened = false;
};

}  // namespace contactlab::drivers::sim
