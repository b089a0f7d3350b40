// test_live_servo.cpp — the editor's servo on drivers' ServoRunner (the one deadline loop), with a
// device that records what it is commanded: the force ramps in after arming, and stopping the
// servo (what every device or rate switch does) leaves zero force as the device's last command.
#include "drivers/sim/sim_rig.hpp"
#include "engine/editor/live_servo.hpp"
#include "engine/editor/servo_view.hpp"

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

using namespace contactlab;
using namespace contactlab::editor;

namespace {

// A planar force device whose finger height the test sets, and which keeps its last command.
class CommandProbe final : public drivers::Device {
public:
    std::atomic<double> finger_y{0.03};   // m
    std::atomic<double> last_fx{0.0}, last_fy{0.0};  // N
    std::atomic<int> writes{0};
    std::atomic<bool> closed{false};

    const char* name() const noexcept override { return "probe"; }
    drivers::DeviceCapabilities capabilities() const noexcept override {
        drivers::DeviceCapabilities c;
        c.planar_force = true;
        return c;
    }
    drivers::DeviceLimits limits() const noexcept override { return {}; }
    bool open() override {
        state_ = drivers::DeviceState::ready;
        return true;
    }
    void close() override {
        state_ = drivers::DeviceState::disconnected;
        closed = true;
    }
    drivers::DeviceState state() const noexcept override { return state_; }
    drivers::DeviceFault fault() const noexcept override { return {}; }
    void set_engaged(bool) noexcept override {}
    bool read(drivers::DeviceReading& out) noexcept override {
        out = drivers::DeviceReading{};
        out.t = t_;
        out.finger = Vec2(0.0, finger_y.load());
        out.valid = true;
        return true;
    }
    void write(const drivers::DeviceCommand& cmd) noexcept override {
        last_fx = cmd.force.x;
        last_fy = cmd.force.y;
        ++writes;
    }
    void advance(double dt) noexcept override { t_ += dt; }  // s: the tick's own clock

private:
    std::atomic<drivers::DeviceState> state_{drivers::DeviceState::disconnected};
    double t_ = 0.0;
};

using drivers::sim::floor_scene;  // y = 0, solid below

// Polls `pred` every ms for up to `seconds` (s).
template <class P>
bool within(double seconds, P pred) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
        if (pred()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return pred();
}

}  // namespace

TEST_CASE("live servo: force ramps in after arming, and stop() leaves zero force on the device") {
    CommandProbe dev;
    const Scene scene = floor_scene();
    const double R = scene.finger.radius;            // m: the c-space floor is y = R
    LiveServo servo(dev, 1000.0, servo_params_for(scene, RollerGains{}, kMouseWatchdog));
    servo.publish_scene(scene);
    dev.finger_y = R + 0.005;  // 5 mm above the floor: free space, the safety gate opens
    REQUIRE(servo.start());
    CHECK(within(3.0, [&] { return servo.snapshot().state == ServoState::engaged; }));
    CHECK(servo.scheduling() != "starting");

    dev.finger_y = R - 0.001;  // 1 mm in: |F| = Ke * 1 mm = 1 N once ramped in
    const double want = scene.force.stiffness * 0.001;  // N
    CHECK(within(3.0, [&] { return std::abs(std::hypot(dev.last_fx.load(), dev.last_fy.load()) - want) < 1e-9; }));
    CHECK(dev.last_fy.load() > 0.0);  // pushes the finger up, out of the floor

    const int writes_before = dev.writes.load();
    servo.stop();
    CHECK(dev.closed.load());
    CHECK(dev.writes.load() > writes_before);
    // The safety path on the way out: the last command is exactly zero, not the held 1 N.
    CHECK(dev.last_fx.load() == 0.0);
    CHECK(dev.last_fy.load() == 0.0);
    CHECK_FALSE(servo.running());
}
