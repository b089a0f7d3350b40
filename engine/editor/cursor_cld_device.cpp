// cursor_cld_device.cpp — the simulated CLD held by a cursor-following hand (see the header).
#include "engine/editor/cursor_cld_device.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::editor {

CursorCldDevice::CursorCldDevice(const CursorCldParams& p, const MousePose& start)
    : p_(p), arm_(p.arm), roller_(p.roller), cursor_(start) {
    p_.arm.base = start.finger - Vec2(0.0, p_.base_below);
    arm_ = drivers::sim::PlanarArm(p_.arm);
    const double reach = p_.arm.l1 + p_.arm.l2;  // m
    limits_.max_force = p_.max_force;
    limits_.axis_max_force = Vec2{p_.max_force};
    limits_.workspace.lo = p_.arm.base - Vec2{reach};
    limits_.workspace.hi = p_.arm.base + Vec2{reach};
    // The damping the arm guarantees where the finger works (5 cm around the start), as sim-cld
    // declares it over its hand path's box: it bounds the stable stiffness 2 b / T at 1 kHz.
    limits_.damping = arm_.min_cartesian_damping(start.finger - Vec2{0.05}, start.finger + Vec2{0.05});
    limits_.max_stable_stiffness = 2.0 * limits_.damping / 1e-3;
    // The endpoint's own mass bounds every direction's effective mass from below (the links add to it).
    limits_.mass = arm_.params().endpoint_mass;
    limits_.roller_min = -roller_.half_travel();
    limits_.roller_max = roller_.half_travel();
}

drivers::DeviceCapabilities CursorCldDevice::capabilities() const noexcept {
    drivers::DeviceCapabilities c;
    c.planar_force = true;
    c.finger_angle = true;
    c.roller = true;
    c.simulated = true;
    return c;
}

bool CursorCldDevice::open() {
    state_.store(drivers::DeviceState::opening);
    const MousePose start = cursor_.load();
    if (placed_) {
        // Re-opened (the servo restarted at another rate): the arm stays where the hand holds it.
        arm_.zero_torque();
        roller_.set_voltage(0.0);
        fault_ = {};
        state_.store(drivers::DeviceState::ready);
        return true;
    }
    if (!arm_.place_at(start.finger)) {
        fault_ = {drivers::DeviceFaultCode::open_failed, "the cursor is outside the simulated arm's reach"};
        state_.store(drivers::DeviceState::fault);
        return false;
    }
    t_ = 0.0;
    target_ = start.finger;
    phi_ = start.phi;
    arm_.zero_torque();
    roller_.place_at(0.0);
    roller_.set_voltage(0.0);
    fault_ = {};
    placed_ = true;
    state_.store(drivers::DeviceState::ready);
    return true;
}

void CursorCldDevice::set_engaged(bool on) noexcept {
    const auto s = state_.load();
    if (s == drivers::DeviceState::ready && on) state_.store(drivers::DeviceState::engaged);
    else if (s == drivers::DeviceState::engaged && !on) state_.store(drivers::DeviceState::ready);
}

bool CursorCldDevice::read(drivers::DeviceReading& out) noexcept {
    out = drivers::DeviceReading{};
    const auto s = state_.load();
    if (s == drivers::DeviceState::disconnected || s == drivers::DeviceState::opening) return false;
    const double step = kTwoPi / p_.angle_encoder_counts;  // rad per encoder count
    out.t = t_;
    out.finger = arm_.measured_endpoint();
    out.phi = std::floor(phi_ / step + 0.5) * step;
    out.roller_l = roller_.measured();
    out.valid = true;
    return true;
}

void CursorCldDevice::write(const drivers::DeviceCommand& cmd) noexcept {
    const auto s = state_.load();
    if (s == drivers::DeviceState::disconnected || s == drivers::DeviceState::opening) return;
    if (!is_finite(cmd.force) || !std::isfinite(cmd.roller_drive)) {
        // Amplifiers off rather than pass NaN on; a good command re-enables them.
        arm_.zero_torque();
        roller_.set_voltage(0.0);
        fault_ = {drivers::DeviceFaultCode::non_finite_command, "non-finite command refused"};
        state_.store(drivers::DeviceState::fault);
        return;
    }
    if (s == drivers::DeviceState::fault) {
        fault_ = {};
        state_.store(drivers::DeviceState::ready);
    }
    const double m = glm::length(cmd.force);  // N
    arm_.command_force(m > p_.max_force ? cmd.force * (p_.max_force / m) : cmd.force);
    roller_.set_voltage(cmd.roller_drive);
}

void CursorCldDevice::advance(double dt) noexcept {
    if (!(dt > 0.0) || state_.load() == drivers::DeviceState::disconnected) return;
    const MousePose cursor = cursor_.load();
    const drivers::sim::HandParams& hp = p_.hand;
    const int n = std::max(std::max(1, p_.min_substeps), static_cast<int>(std::ceil(dt / p_.substep - 1e-9)));
    const double h = dt / n;  // s
    const double a_pos = 1.0 - std::exp(-h / p_.cursor_lag), a_phi = 1.0 - std::exp(-h / hp.phi_lag);
    for (int i = 0; i < n; ++i) {
        // The hand's intended position moves toward the cursor; its velocity is that lag's slope.
        const Vec2 v_target = (cursor.finger - target_) / p_.cursor_lag;  // m/s
        target_ += (cursor.finger - target_) * a_pos;
        const Vec2 hand = hp.stiffness * (target_ - arm_.endpoint()) + hp.damping * (v_target - arm_.velocity());
        arm_.step(h, hand);
        roller_.step(h);
        phi_ += (cursor.phi - phi_) * a_phi;
    }
    t_ += dt;
}

}  // namespace contactlab::editor
