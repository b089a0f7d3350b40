// servo_sim — seed 000's contour-following task in simulation: a scripted hand holds the
// simulated CLD rig (force arm + contact-location roller) and slides the finger along the block's
// top, over its edge and down its far face, while the servo loop renders force and contact
// location at 1 kHz. Virtual time: no sleeping, and the same numbers on every run (what
// `contactlab simulate scenes/block.json --task contour-block` does, without the CSV).
//
//   servo_sim [SPEED]     hand speed in m/s, default 0.05
#include "drivers/sim/sim_rig.hpp"  // SimRig: simulated device + ServoTick + ServoLoop, wired
#include "drivers/tasks.hpp"        // block_scene, contour_block_task

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
    using namespace contactlab;
    const double rate = 1000.0;  // Hz, seed 000's servo rate

    // 1. The scene (the block of scenes/block.json, built in code) and the hand's path over it.
    const Scene scene = drivers::block_scene();
    drivers::BlockTaskParams task;
    task.finger_radius = scene.finger.radius;
    task.speed = argc > 1 ? std::atof(argv[1]) : 0.05;  // m/s
    if (!(task.speed > 0.0 && task.speed <= 1.0)) {
        std::fprintf(stderr, "servo_sim: SPEED must be in (0, 1] m/s\n");
        return 1;
    }

    // 2. Device, servo tick and loop wired together; the scene is published and the device opened.
    drivers::sim::SimRig rig(scene, drivers::contour_block_task(task), rate);
    if (!rig.opened) {
        std::fprintf(stderr, "servo_sim: the simulated device did not open\n");
        return 1;
    }

    // 3. Step the loop for the length of the path: each step reads the device, runs the proxy,
    //    force law, safety and roller PID, and writes the command back; the simulation then
    //    advances one period. The snapshot is what a UI would read from another thread.
    const auto ticks = static_cast<long>(std::lround(rig.device.hand().path().end() * rate));
    long in_contact = 0;
    double max_force = 0.0, max_roller_error = 0.0;  // N, m
    std::printf("   t(s)  contact  |F|(N)  l_d(mm)  roller(mm)\n");
    for (long k = 0; k < ticks; ++k) {
        rig.loop.step(1.0 / rate, true);
        const ServoSnapshot s = rig.servo.snapshot();
        const double f = std::hypot(s.force.x, s.force.y);
        max_force = std::max(max_force, f);
        if (s.contact) {
            ++in_contact;
            if (s.state == ServoState::engaged)
                max_roller_error = std::max(max_roller_error, std::abs(s.roller_target - s.roller_l));
        }
        if (k % 250 == 0)
            std::printf("%7.3f  %7d  %6.3f  %7.2f  %10.2f\n", s.t, s.contact ? 1 : 0, f, s.l_d * 1e3, s.roller_l * 1e3);
    }

    const ServoSnapshot end = rig.servo.snapshot();
    std::printf("ticks %ld, in contact %ld, max |F| %.3f N (limit %.2f N), roller error max %.3f mm, "
                "state %s, faults %u\n", ticks, in_contact, max_force, scene.force.max_force, max_roller_error * 1e3,
                to_string(end.state), end.fault_count);
    return 0;
}
