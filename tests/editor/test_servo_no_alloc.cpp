// test_servo_no_alloc.cpp — the editor's servo thread, running for real (drivers' ServoRunner,
// the emergency-stop hook, ServoLoop, ServoTick, the tick ring) against the editor's own devices
// (sim-cld held by the cursor, the mouse), makes no heap allocation, takes no lock and writes
// nothing while it runs in contact. Counted on every thread (tests/common/side_effects.hpp); the
// test thread only sleeps meanwhile.
#include "engine/editor/cursor_cld_device.hpp"
#include "drivers/sim/sim_rig.hpp"
#include "engine/editor/live_servo.hpp"
#include "engine/editor/mouse_device.hpp"
#include "engine/editor/servo_view.hpp"

#include <doctest/doctest.h>

#include "side_effects.hpp"

#include <chrono>
#include <memory>
#include <pthread.h>
#include <thread>
#include <unistd.h>

using namespace contactlab;
using namespace contactlab::editor;
using namespace contactlab::test;

namespace {

using drivers::sim::floor_scene;  // y = 0, solid below

// Runs the live servo on `dev` in contact (the pose 4 mm into the floor), counting for `seconds`.
void run_counted(drivers::Device& dev, PoseInput& pose_in, double seconds) {
    const Scene scene = floor_scene();
    const double R = scene.finger.radius;  // m
    LiveServo servo(dev, 1000.0, servo_params_for(scene, RollerGains{}, kMouseWatchdog));
    servo.publish_scene(scene);
    MousePose pose;
    pose.finger = Vec2(0.0, R + 0.005);  // free space first: the gate opens
    pose_in.set_pose(pose);
    REQUIRE(servo.start());
    for (int i = 0; i < 3000 && servo.snapshot().state != ServoState::engaged; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    REQUIRE(servo.snapshot().state == ServoState::engaged);
    pose.finger = Vec2(0.0, R - 0.004);
    pose_in.set_pose(pose);
    for (int i = 0; i < 3000 && !servo.snapshot().contact; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    REQUIRE(servo.snapshot().contact);
    const std::uint64_t before = servo.snapshot().ticks;
    reset_side_effects();
    count_all_threads(true);
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    count_all_threads(false);
    const test::SideEffects e = side_effects();
    const ServoSnapshot after = servo.snapshot();
    CHECK(after.contact);
    CHECK(after.ticks - before > static_cast<std::uint64_t>(0.5 * seconds * 1000.0));  // it did run
    CHECK(e.allocs == 0);
    CHECK(e.locks == 0);
    CHECK(e.io == 0);
    servo.stop();
}

}  // namespace

TEST_CASE("editor servo thread with sim-cld in contact: no allocation, lock or write") {
    MousePose start;
    start.finger = Vec2(0.0, 0.031);
    CursorCldDevice dev(CursorCldParams{}, start);
    run_counted(dev, dev, 0.5);
}

TEST_CASE("editor servo thread with the mouse in contact: no allocation, lock or write") {
    MouseDevice dev;
    run_counted(dev, dev, 0.5);
}
