// sim_cld_device.cpp — the simulated CLD rig (see sim_cld_device.hpp).
#include "drivers/sim/sim_cld_device.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::drivers::sim {

SimCldDevice::SimCldDevice(const SimCldParams& p, HandPath path)
    : p_(p), arm_(p.arm), roller_(p.roller), hand_(p.hand, std::move(path)) {
    if (p_.auto_base) {
        Aabb box;
        for (const PathSample& s : hand_.path().samples()) box.grow(s.x);
        // Below the middle of the path, far enough that the whole path is inside the reach.
        p_.arm.base = Vec2{0.5 * (box.lo.x + box.hi.x), box.lo.y - 0.12};
        arm_ = PlanarArm(p_.arm);
    }
    const double reach = p_.arm.l1 + p_.arm.l2;
    limits_.max_force = p_.max_force;
    // Per-axis: what the weaker motor can hold anywhere useful; the arm also saturates torques.
    limits_.axis_max_force = Vec2{p_.max_force};
    limits_.workspace.lo = p_.arm.base - Vec2{reach};
    limits_.workspace.hi = p_.arm.base + Vec2{reach};
    Aabb box;
    for (const PathSample& s : hand_.path().samples()) box.grow(s.x);
    limits_.damping = arm_.min_cartesian_damping(box.lo - Vec2{0.01}, box.hi + Vec2{0.01});
    limits_.max_stable_stiffness = 2.0 * limits_.damping / 1e-3;
    // The endpoint's own mass bounds every direction's effective mass from below (the links add to it).
    limits_.mass = p_.arm.endpoint_mass;
    limits_.roller_min = -roller_.half_travel();
    limits_.roller_max = roller_.half_travel();
}

DeviceCapabilities SimCldDevice::capabilities() const noexcept {
    DeviceCapabilities c;
    c.planar_force = true;
    c.finger_angle = true;
    c.roller = true;
    c.simulated = true;
    return c;
}

bool SimCldDevice::open() {
    state_ = DeviceState::opening;
    t_ = hand_.path().start();
    if (!arm_.place_at(hand_.path().at(t_).x)) {
        state_ = DeviceState::fault;
        fault_ = {DeviceFaultCode::open_failed, "hand path starts outside the arm's reach"};
        return false;
    }
    hand_.reset(t_);
    roller_.place_at(0.0);
    arm_.zero_torque();
    roller_.set_voltage(0.0);
    since_command_ = 0.0;
    motors_on_ = true;
    fault_ = {};
    state_ = DeviceState::ready;
    return true;
}

void SimCldDevice::set_engaged(bool on) noexcept {
    if (state_ == DeviceState::ready && on) state_ = DeviceState::engaged;
    else if (state_ == DeviceState::engaged && !on) state_ = DeviceState::ready;
}

bool SimCldDevice::read(DeviceReading& out) noexcept {
    out = DeviceReading{};
    if (state_ == DeviceState::disconnected || state_ == DeviceState::opening) return false;
    const double step = kTwoPi / p_.angle_encoder_counts;
    out.t = t_;
    out.finger = arm_.measured_endpoint();
    out.phi = std::floor(hand_.phi() / step + 0.5) * step;
    out.roller_l = roller_.measured();
    out.valid = true;
    return true;
}

void SimCldDevice::write(const DeviceCommand& cmd) noexcept {
    if (state_ == DeviceState::disconnected || state_ == DeviceState::opening) return;
    since_command_ = 0.0;
    if (!is_finite(cmd.force) || !std::isfinite(cmd.roller_drive)) {
        arm_.zero_torque();
        roller_.set_voltage(0.0);
        state_ = DeviceState::fault;
        fault_ = {DeviceFaultCode::non_finite_command, "non-finite command refused"};
        return;
    }
    if (state_ == DeviceState::fault) {  // a good command after a fault re-enables the amplifiers
        state_ = DeviceState::ready;
        fault_ = {};
    }
    motors_on_ = true;
    const double m = glm::length(cmd.force);
    const Vec2 f = m > p_.max_force ? cmd.force * (p_.max_force / m) : cmd.force;
    arm_.command_force(f);
    roller_.set_voltage(cmd.roller_drive);
}

void SimCldDevice::advance(double dt) noexcept {
    if (!(dt > 0.0) || state_ == DeviceState::disconnected) return;
    since_command_ += dt;
    if (motors_on_ && since_command_ > p_.watchdog_timeout) {
        // Nobody is commanding: switch the amplifiers off rather than hold a stale force.
        motors_on_ = false;
        arm_.zero_torque();
        roller_.set_voltage(0.0);
        ++watchdog_trips_;
        state_ = DeviceState::fault;
        fault_ = {DeviceFaultCode::watchdog, "no command within the watchdog timeout"};
    }
    const int n = std::max(std::max(1, p_.min_substeps), static_cast<int>(std::ceil(dt / p_.substep - 1e-9)));
    const double h = dt / n;
    // The path's interval the tick starts in: the substeps' times mostly lie in it (samples a
    // period apart), and it answers them without the path's search (the same bits).
    const HandPath::Interval span = hand_.path().interval_at(t_);
    for (int i = 0; i < n; ++i) {
        const double t = t_ + i * h;
        arm_.step_held(h, [&](Vec2 x, Vec2 v) { return hand_.force(t, x, v, span); });
        roller_.step(h);
        hand_.step_phi(t + h, h, span);
    }
    t_ += dt;
}

}  // namespace contactlab::drivers::sim
