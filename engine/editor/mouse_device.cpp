// mouse_device.cpp — cursor as finger, simulated roller (see mouse_device.hpp).
#include "engine/editor/mouse_device.hpp"

#include <cmath>

namespace contactlab::editor {

MouseDevice::MouseDevice() : roller_(drivers::sim::RollerParams{}) {
    limits_.max_force = 1.5;              // N, seed 000's device (what the servo clamps to)
    limits_.axis_max_force = {1.5, 1.5};  // N
    limits_.max_stable_stiffness = 2000;  // N/m: shown against Ke, as for the CLD arm
    limits_.damping = 1.0;                // N s/m
    limits_.roller_min = -0.5 * roller_.params().travel;
    limits_.roller_max = 0.5 * roller_.params().travel;
    limits_.workspace.grow(Vec2(-10.0));
    limits_.workspace.grow(Vec2(10.0));
}

drivers::DeviceCapabilities MouseDevice::capabilities() const noexcept {
    drivers::DeviceCapabilities c;
    c.finger_angle = true;  // phi comes from the wheel / keys
    c.roller = true;        // simulated CLD roller
    c.simulated = true;     // the roller is advanced by advance(dt)
    return c;
}

bool MouseDevice::open() {
    state_.store(drivers::DeviceState::opening);
    roller_.place_at(0.0);
    roller_.set_voltage(0.0);
    opened_ = std::chrono::steady_clock::now();
    state_.store(drivers::DeviceState::ready);
    return true;
}

void MouseDevice::set_engaged(bool on) noexcept {
    const auto s = state_.load();
    if (s == drivers::DeviceState::ready && on) state_.store(drivers::DeviceState::engaged);
    else if (s == drivers::DeviceState::engaged && !on) state_.store(drivers::DeviceState::ready);
}

bool MouseDevice::read(drivers::DeviceReading& out) noexcept {
    out = drivers::DeviceReading{};
    const auto s = state_.load();
    if (s == drivers::DeviceState::disconnected || s == drivers::DeviceState::opening) return false;
    const MousePose p = pose_.load();
    out.t = std::chrono::duration<double>(std::chrono::steady_clock::now() - opened_).count();  // s
    out.finger = p.finger;
    out.phi = p.phi;
    out.roller_l = roller_.measured();
    out.valid = std::isfinite(p.finger.x) && std::isfinite(p.finger.y) && std::isfinite(p.phi);
    return true;
}

void MouseDevice::write(const drivers::DeviceCommand& cmd) noexcept {
    // The force has nowhere to go on a mouse; the roller takes its drive (V), finite or nothing.
    roller_.set_voltage(std::isfinite(cmd.roller_drive) ? cmd.roller_drive : 0.0);
}

void MouseDevice::advance(double dt) noexcept {
    if (!(dt > 0.0) || state_.load() == drivers::DeviceState::disconnected) return;
    // The roller's wires are stiff: integrate in sub-steps of at most 0.1 ms, as sim-cld does.
    constexpr double kSubstep = 1e-4;  // s
    const int n = static_cast<int>(std::ceil(dt / kSubstep));
    for (int i = 0; i < n; ++i) roller_.step(dt / n);
}

}  // namespace contactlab::editor
