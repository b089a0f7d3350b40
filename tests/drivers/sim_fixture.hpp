// sim_fixture.hpp — a servo loop against the simulated CLD rig, for tests (virtual time).
#pragma once

#include "drivers/servo_loop.hpp"
#include "drivers/sim/sim_cld_device.hpp"
#include "drivers/sim/sim_rig.hpp"
#include "drivers/tasks.hpp"
#include "haptics/scene_io.hpp"

#include <memory>
#include <string>

namespace contactlab::test {

inline Scene load_shipped_scene(const std::string& name) {
    return load_scene_file(std::string(CONTACTLAB_SOURCE_DIR) + "/scenes/" + name);
}

// A flat floor along y = 0 from x = -1 m to 1 m (solid below); stiffness in N/m.
inline Scene floor_scene(double stiffness = 1000.0) { return drivers::sim::floor_scene(stiffness); }

// A hand path holding still at x (m), phi (rad) for `duration` s.
inline drivers::HandPath hold_path(Vec2 x, double duration, double phi = 0.0) {
    return drivers::HandPath({{0.0, x, phi}, {duration, x, phi}});
}

// The rig lives in drivers/ so the bench probes and the tests share it.
using drivers::sim::SimRig;

}  // namespace contactlab::test
