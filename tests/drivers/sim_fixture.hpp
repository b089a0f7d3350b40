// sim_fixture.hpp — a servo loop against the simulated CLD rig, for tests (virtual time).
#pragma once

#include "drivers/servo_loop.hpp"
#include "drivers/sim/sim_cld_device.hpp"
#include "drivers/tasks.hpp"
#include "haptics/scene_io.hpp"

#include <memory>
#include <string>

namespace contactlab::test {

inline Scene load_shipped_scene(const std::string& name) {
    return load_scene_file(std::string(CONTACTLAB_SOURCE_DIR) + "/scenes/" + name);
}

// A flat floor along y = 0 from x = -1 m to 1 m (solid below).
inline Scene floor_scene(double stiffness = 1000.0) {
    Scene s;
    Contour c;
    c.segments.push_back(LineSegment{{-1.0, 0.0}, {1.0, 0.0}});
    s.contours.push_back(c);
    s.force.stiffness = stiffness;
    return s;
}

// A hand path holding still at x (m), phi (rad) for `duration` s.
inline drivers::HandPath hold_path(Vec2 x, double duration, double phi = 0.0) {
    return drivers::HandPath({{0.0, x, phi}, {duration, x, phi}});
}

struct SimRig {
    SimRig(const Scene& scene, drivers::HandPath path, double rate = 1000.0,
           const drivers::sim::SimCldParams& sp = {}, ServoParams params = default_params())
        : device(sp, std::move(path)),
          servo(drivers::servo_config_for(device, rate), with_scene(params, scene)),
          loop(device, servo, 1.0 / rate) {
        servo.scenes().publish(std::make_unique<ServoScene>(scene));
        opened = loop.start();
    }
    static ServoParams default_params() { return ServoParams{}; }
    static ServoParams with_scene(ServoParams p, const Scene& s) {
        p.stiffness = s.force.stiffness;
        p.max_force = s.force.max_force;
        return p;
    }
    drivers::sim::SimCldDevice device;
    ServoTick servo;
    drivers::ServoLoop loop;
    bool opened = false;
};

}  // namespace contactlab::test
