// test_finger_devices.cpp — seed 003's live sweep on the devices that take it, without a window:
// the simulated wearable in the editor (CursorWearableDevice) and a USB board behind
// PlatformFingerDevice give the sweep's finger, timed from the first reading after it started,
// then the cursor's again after stop_sweep(); a device whose finger is the user's hand refuses it.
#include "drivers/finger_sweep.hpp"
#include "drivers/sim/sim_wearable_device.hpp"
#include "engine/editor/cursor_wearable_device.hpp"
#include "engine/editor/mouse_device.hpp"
#include "engine/editor/platform_finger_device.hpp"

#include <doctest/doctest.h>

#include <memory>

using namespace contactlab;
using namespace contactlab::editor;

namespace {

drivers::FingerSweep seed003_sweep() {
    drivers::FingerSweep s;
    s.x0 = -0.17;
    s.x1 = 0.17;
    s.speed = 0.1;
    s.finger_radius = 0.010;
    s.press = 0.003;
    s.chord = 0.30;
    s.height = 0.02;
    return s;
}

// Reads `dev` every millisecond of its own time for `seconds`, checking each reading's finger
// against the sweep's at the time since the first reading.
void check_plays(drivers::Device& dev, const drivers::FingerSweep& s, double seconds) {
    drivers::DeviceReading r;
    dev.read(r);
    const double t0 = r.t;
    CHECK(r.finger.x == s.x0);
    CHECK(r.finger.y == drivers::finger_sweep_at(s, 0.0).y);  // above x0, coming down
    for (int i = 0; i < static_cast<int>(seconds * 1000.0); ++i) {
        dev.advance(1e-3);
        dev.read(r);
        const Vec2 want = drivers::finger_sweep_at(s, r.t - t0);
        REQUIRE(r.finger.x == want.x);
        REQUIRE(r.finger.y == want.y);
        REQUIRE(r.phi == 0.0);
    }
}

}  // namespace

TEST_CASE("finger sweep: sim-wearable in the editor plays the sweep on its own clock, then gives the cursor back") {
    const MousePose cursor{{0.05, 0.02}, 0.3};
    CursorWearableDevice dev(cursor);
    REQUIRE(dev.open());
    const drivers::FingerSweep s = seed003_sweep();
    REQUIRE(dev.start_sweep(s));
    check_plays(dev, s, 0.5);
    // Started again, it starts from x0 again.
    dev.start_sweep(s);
    check_plays(dev, s, 0.1);
    dev.stop_sweep();
    drivers::DeviceReading r;
    dev.read(r);
    CHECK(r.finger.x == cursor.finger.x);
    CHECK(r.finger.y == cursor.finger.y);
    CHECK(r.phi == cursor.phi);
    dev.close();
}

TEST_CASE("finger sweep: a board behind PlatformFingerDevice takes it when it is a platform, and refuses it when the hand is real") {
    const drivers::FingerSweep s = seed003_sweep();
    {
        PlatformFingerDevice dev(std::make_unique<drivers::sim::SimWearableDevice>(), MousePose{{0.0, 0.02}, 0.0});
        REQUIRE(dev.open());
        CHECK(dev.capabilities().platform);
        REQUIRE(dev.start_sweep(s));
        check_plays(dev, s, 0.3);
        dev.close();
    }
    {
        // The mouse's finger is the user's cursor: no sweep, and the readings pass through.
        auto inner = std::make_unique<MouseDevice>();
        MouseDevice* mouse = inner.get();
        PlatformFingerDevice dev(std::move(inner), MousePose{});
        REQUIRE(dev.open());
        CHECK_FALSE(dev.capabilities().platform);
        CHECK_FALSE(dev.start_sweep(s));
        mouse->set_pose(MousePose{{0.03, 0.04}, 0.1});
        drivers::DeviceReading r;
        dev.read(r);
        CHECK(r.finger.x == 0.03);
        CHECK(r.finger.y == 0.04);
        dev.close();
    }
}
