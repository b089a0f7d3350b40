// servo_tick.cpp — the servo tick (see servo_tick.hpp for the contract).
#include "haptics/servo_tick.hpp"

#include "haptics/servo_params_check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace contactlab {
namespace {

// Moves `cur` toward `goal` by at most rate * dt.
double slew(double cur, double goal, double rate, double dt) {
    if (!std::isfinite(goal)) return cur;
    if (!(rate > 0.0)) return goal;
    const double step = rate * dt;
    return cur + std::clamp(goal - cur, -step, step);
}

bool finite_input(const ServoInput& in, bool roller) {
    return std::isfinite(in.t) && is_finite(in.finger) && std::isfinite(in.phi) &&
           (!roller || std::isfinite(in.roller_l));
}

}  // namespace

namespace {
// The part of the device's roller travel (m) the servo may use: `length` (m) centred in it, or
// all of it when length is 0 or longer than the device's.
RollerTravel usable_travel(const RollerTravel& device, double length) {
    if (!(length > 0.0) || length >= device.max - device.min) return device;
    const double centre = 0.5 * (device.min + device.max);  // m
    return {centre - 0.5 * length, centre + 0.5 * length};
}

const ServoConfig& checked(const ServoConfig& c, const ServoParams& p) {
    std::string problem = servo_config_problem(c);
    if (problem.empty()) problem = servo_params_problem(p, c);
    if (!problem.empty()) throw std::invalid_argument("servo: " + problem);
    return c;
}
}  // namespace

ServoTick::ServoTick(const ServoConfig& config, const ServoParams& params)
    : config_(checked(config, params)), target_(params), current_(params), params_in_(params) {
    params_seen_ = params_in_.version();
    current_.max_force = std::min(current_.max_force, config_.device_max_force);
    roller_ = RollerController(params.roller, usable_travel(config.roller_travel, params.roller_travel));
    safety_.set_params(params.safety);
    limit_cycle_.set_params(params.limit_cycle);
}

ServoTick::~ServoTick() { delete scene_; }

std::string ServoTick::publish_params(const ServoParams& p) {
    std::string problem = servo_params_problem(p, config_);
    if (problem.empty()) params_in_.store(p);
    return problem;
}

void ServoTick::connect(double t) noexcept {
    safety_.connect(t);
    observer_.reset();
    balance_.reset();
    controller_.reset();
    limit_cycle_.reset();
    applied_ = Vec2{0.0};
}

void ServoTick::disconnect() noexcept {
    safety_.disconnect();
    observer_.reset();
    balance_.reset();
    controller_.reset();
    limit_cycle_.reset();
    applied_ = Vec2{0.0};
    cmd_ = ServoCommand{};
}

void ServoTick::apply_params(double dt) noexcept {
    const std::uint64_t v = params_in_.version();
    if (v != params_seen_) {
        params_seen_ = v;
        target_ = params_in_.load();
        // Gains and safety settings take effect at this boundary; the controller keeps its
        // integral in output units, so a gain change does not step the drive.
        roller_.set_gains(target_.roller);
        roller_.set_travel(usable_travel(config_.roller_travel, target_.roller_travel));
        current_.roller_travel = target_.roller_travel;
        safety_.set_params(target_.safety);
        current_.roller = target_.roller;
        current_.safety = target_.safety;
        current_.passivity_threshold = target_.passivity_threshold;
        current_.passivity = target_.passivity;
        current_.limit_cycle = target_.limit_cycle;
        limit_cycle_.set_params(target_.limit_cycle);
        current_.stiffness_slew = target_.stiffness_slew;
        current_.max_force_slew = target_.max_force_slew;
    }
    current_.stiffness = std::max(0.0, slew(current_.stiffness, target_.stiffness, current_.stiffness_slew, dt));
    const double force_goal = std::min(target_.max_force, config_.device_max_force);
    current_.max_force = std::max(0.0, slew(current_.max_force, force_goal, current_.max_force_slew, dt));
    const double linear_energy = current_.stiffness > 0.0
                                     ? current_.max_force * current_.max_force / (2.0 * current_.stiffness)
                                     : 0.0;
    observer_.set_params({current_.passivity_threshold * linear_energy, 0.5});
}

void ServoTick::seed_proxy(Vec2 proxy, double phi) noexcept {
    if (!is_finite(proxy) || !std::isfinite(phi)) return;
    seeded_ = true;
    seed_ = proxy;
    seed_phi_ = phi;
}

void ServoTick::swap_scene(const ServoInput& in) noexcept {
    ServoScene* next = scenes_.take(scene_);
    if (next == nullptr) return;
    // Continuity: the new proxy starts where the old one was (its history), so the force changes
    // only by what the geometry changed; an edit that moved the surface over the old proxy pushes
    // it out to the new boundary, by at most kSwapPush, the least displacement. The first scene
    // starts at the seed from a servo this one replaced, if any, else at the finger.
    constexpr double kSwapPush = 0.002;  // m: the largest geometry change followed continuously
    if (scene_ != nullptr) {
        next->proxy.place(scene_->proxy.output().proxy, scene_->proxy.output().phi, kSwapPush);
        next->proxy.carry_motion(scene_->proxy.output());  // the next tick keeps to the warm start
    } else if (seeded_) {
        next->proxy.place(seed_, seed_phi_, kSwapPush);
        seeded_ = false;
    } else {
        next->proxy.reset(in.finger, in.phi);
    }
    scene_ = next;  // the old one now sits in the exchange's retire slot for the publisher
    ++scene_swaps_;
}

void ServoTick::fault_tick(const ServoInput& in, double dt, ServoFault f) noexcept {
    safety_.raise(f, std::isfinite(in.t) ? in.t : (std::isfinite(last_t_) ? last_t_ + dt : 0.0));
    energy_terms_ = EnergyTerms{};  // nothing rendered: no balance (a CSV summing terms must not count the last twice)
    observer_.reset();
    balance_.reset();
    controller_.reset();
    limit_cycle_.reset();
    roller_.reset(std::numeric_limits<double>::quiet_NaN());
    applied_ = Vec2{0.0};
    cmd_ = ServoCommand{};
}

const ServoCommand& ServoTick::tick(const ServoInput& in) noexcept {
    ++ticks_;
    double dt = config_.period;
    if (std::isfinite(in.t) && std::isfinite(last_t_) && in.t > last_t_) dt = in.t - last_t_;
    const bool stalled = std::isfinite(last_t_) && std::isfinite(in.t) &&
                         in.t - last_t_ > current_.safety.watchdog_timeout;
    if (std::isfinite(in.t)) last_t_ = in.t;

    if (clear_request_.exchange(false, std::memory_order_acq_rel)) safety_.clear_fault();
    apply_params(dt);

    const bool finite = finite_input(in, config_.has_roller);
    const std::uint32_t swaps_before = scene_swaps_;
    if (finite) swap_scene(in);

    if (!finite) {
        fault_tick(in, dt, ServoFault::non_finite_input);
    } else if (in.device_fault) {
        fault_tick(in, dt, ServoFault::device);
    } else if (stalled) {
        fault_tick(in, dt, ServoFault::watchdog);
    }

    const bool rendering = finite && scene_ != nullptr;
    if (rendering) {
        Proxy& proxy = scene_->proxy;
        ProxyDef def = proxy.def();
        def.stiffness = current_.stiffness;
        def.max_force = current_.max_force;
        proxy.set_def(def);
        // dt: the virtual damper's velocity is the change of depth over the real period (at the
        // proxy's 1 ms default a 10 kHz servo rendered a tenth of the damping asked for).
        proxy_out_ = proxy.update(in.finger, in.phi, dt);

        const Vec2 rendered = proxy_out_.force;
        const double rendered_mag = is_finite(rendered) ? glm::length(rendered) : 0.0;
        if (!is_finite(rendered)) fault_tick(in, dt, ServoFault::non_finite_output);

        const double scale = safety_.step(in.t);
        Vec2 f = clamp_then_saturate(rendered * scale, current_.max_force, config_.axis_max);

        // Instability watch while force is being applied.
        const ServoState st = safety_.state();
        if (st == ServoState::ramping || st == ServoState::engaged) {
            // The device's per-axis saturation may pass on only part of the (already clamped)
            // rendered force; the spring the finger meets is weakened by that fraction, and so is
            // the energy it stores. Without this a device with a small axis limit looks like a
            // loop generating energy (the spring "stores" what the motors never pushed).
            const double asked = scale * rendered_mag;  // N
            const double kept = asked > 0.0 ? std::min(1.0, glm::length(f) / asked) : 1.0;
            const bool linear = proxy_out_.contact && proxy_out_.depth > 0.0 && kept > 1.0 - 1e-9 &&
                                current_.stiffness * proxy_out_.depth < current_.max_force;
            // Where this tick's energy came from; the observer sums what the loop generated. The
            // ramp's scale and the saturation's share weigh the spring's energy (both ticks' at
            // this tick's share: a ramp turning the force up on a finger at rest is not the
            // loop's doing; without that a ramp into a finger resting 5 mm deep, 6 mJ at 1.5 N,
            // read as an instability and faulted the servo it was bringing back).
            const EnergySample sample{in.finger, proxy_out_.start, proxy_out_.turned, proxy_out_.proxy,
                                      proxy_out_.anchor, applied_, scale * kept, dt, scene_swaps_ != swaps_before,
                                      in.phi};
            energy_terms_ = balance_.step(sample, {def.law, current_.stiffness, current_.max_force, config_.device_damping});
            const bool energy_grew = observer_.step(energy_terms_.generated(), dt, linear);
            // Armed where the sampled spring's hold outdoes the device's damping along its
            // weakest direction: K T / 2 > b (N s/m both), T the nominal period (s).
            const bool past_bound = 0.5 * current_.stiffness * config_.period > config_.device_damping;
            const bool cycling = limit_cycle_.step(in.t, glm::length(f), current_.max_force, past_bound);
            // The passivity controller (an option): damp what the loop generated, along the
            // spring's line, within the device's limit; the clamp still holds |F| <= max_force.
            // Only past the bound: inside it the sampled spring cannot generate net energy, and
            // what the sum sees there is the encoders' steps and the hand, which a damper driven
            // by one-count velocity steps only excites (it faulted the block task at 10 kHz).
            controller_.reset();
            // In contact only: kept through free flight after a bounce, its damper could pull
            // the finger back toward the surface.
            if (current_.passivity == PassivityMode::control && past_bound && proxy_out_.contact && !energy_grew &&
                !cycling) {
                const double excess = std::max(observer_.energy(), observer_.linear_energy());  // J
                const Vec2 damp = controller_.step(excess, balance_.motion(), balance_.line(), dt, config_.max_damping);
                if (controller_.damping() > 0.0) f = clamp_then_saturate(f + damp, current_.max_force, config_.axis_max);
            }
            if (energy_grew || cycling) {
                instability_cause_ = energy_grew ? InstabilityCause::energy : InstabilityCause::limit_cycle;
                fault_tick(in, dt, ServoFault::instability);
                f = Vec2{0.0};
            }
        } else {
            observer_.reset();
            balance_.reset();
            controller_.reset();
            energy_terms_ = EnergyTerms{};
            limit_cycle_.reset();
        }

        cmd_.force = f;
        applied_ = f;
        if (config_.has_roller && safety_.state() != ServoState::fault && safety_.state() != ServoState::idle) {
            cmd_.roller_drive = roller_.step(proxy_out_.l_d, in.roller_l, dt);
            cmd_.roller_target = roller_.target();
        } else {
            cmd_.roller_drive = 0.0;
            cmd_.roller_target = std::clamp(proxy_out_.l_d, roller_.travel().min, roller_.travel().max);
            roller_.reset(in.roller_l);
        }
    } else {
        // No scene or unusable input: nothing to render, and never a NaN to the motors.
        safety_.step(std::isfinite(in.t) ? in.t : 0.0);
        cmd_ = ServoCommand{};
        applied_ = Vec2{0.0};
        if (!finite) proxy_out_ = ProxyOutput{};
    }

    // Last line of defence: whatever happened above, the command is finite.
    if (!is_finite(cmd_.force)) cmd_.force = Vec2{0.0};
    if (!std::isfinite(cmd_.roller_drive)) cmd_.roller_drive = 0.0;
    if (!std::isfinite(cmd_.roller_target)) cmd_.roller_target = 0.0;

    // The snapshot is made only for a reader (set_publish_snapshots): a simulated trial's ticks
    // skip its hundred stores.
    if (!publish_snapshots_) return cmd_;
    ServoSnapshot snap;
    snap.ticks = ticks_;
    snap.t = in.t;
    snap.dt = dt;
    snap.finger = in.finger;
    snap.phi = in.phi;
    snap.roller_l = in.roller_l;
    if (rendering) {  // what the proxy rendered this tick (proxy_out_ is this tick's)
        snap.proxy = proxy_out_.proxy;
        snap.contact = proxy_out_.contact;
        snap.contact_count = proxy_out_.contact_count;
        snap.depth = proxy_out_.depth;
        snap.rendered_force = proxy_out_.force;
        snap.l_d = proxy_out_.l_d;
    }
    snap.force = cmd_.force;
    snap.roller_target = cmd_.roller_target;
    snap.roller_drive = cmd_.roller_drive;
    snap.stiffness = current_.stiffness;
    snap.max_force = current_.max_force;
    snap.observer_energy = observer_.energy();
    snap.observer_linear_energy = observer_.linear_energy();
    snap.observer_threshold = observer_.params().threshold;
    snap.observer_used = observer_.used();
    snap.energy = energy_terms_;
    snap.passivity_damping = controller_.damping();
    snap.passivity_saturated = controller_.saturated();
    snap.oscillation_half_cycles = limit_cycle_.half_cycles();
    snap.instability_cause = instability_cause_;
    snap.state = safety_.state();
    snap.fault = safety_.fault();
    snap.fault_count = safety_.fault_count();
    snap.scene_swaps = scene_swaps_;
    snapshot_.store(snap);
    return cmd_;
}

}  // namespace contactlab
