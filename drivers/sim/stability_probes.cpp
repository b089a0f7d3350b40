// stability_probes.cpp — contact scenarios on the simulated rig (see stability_probes.hpp).
#include "drivers/sim/stability_probes.hpp"

#include "drivers/sim/sim_rig.hpp"
#include "drivers/tasks.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace contactlab::drivers::sim {

namespace {

constexpr double kR = 0.026;  // m, the finger's radius (SimCldParams' and the scenes')

HandPath press_path(double depth, double seconds) {
    return HandPath({{0.0, {0.0, kR + 0.005}, 0.0}, {0.3, {0.0, kR - depth}, 0.0}, {seconds, {0.0, kR - depth}, 0.0}});
}

HandPath slide_path(double seconds) {
    // Down to 2 mm in over 0.3 s, then a 6 cm stroke each 1 s: a cosine, peak speed pi 0.03 / 0.5
    // = 0.19 m/s (a brisk stroke across a surface).
    std::vector<PathSample> s{{0.0, {0.0, kR + 0.005}, 0.0}, {0.3, {0.0, kR - 0.002}, 0.0}};
    for (double t = 0.3 + 1e-3; t < seconds; t += 1e-3) {
        const double x = 0.03 * (1.0 - std::cos(2.0 * 3.141592653589793 * (t - 0.3) / 1.0));
        s.push_back({t, {x, kR - 0.002}, 0.0});
    }
    return HandPath(std::move(s));
}

// Taps at f (Hz) between 6 mm above the floor and `depth` (m) into it, a cosine: peak hand speed
// pi f (0.006 + depth) m/s.
HandPath taps_path(double seconds, double f, double depth) {
    const double mid = 0.5 * (0.006 - depth), half = 0.5 * (0.006 + depth);  // m
    std::vector<PathSample> s;
    for (double t = 0.0; t < seconds; t += 1e-3) {
        const double y = kR + mid + half * std::cos(2.0 * 3.141592653589793 * f * t);
        s.push_back({t, {0.0, y}, 0.0});
    }
    return HandPath(std::move(s));
}

// A small deterministic generator (no <random>: the same numbers on every standard library).
struct Lcg {
    std::uint64_t x;
    double uniform() {  // in [-1, 1]
        x = x * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(x >> 11) / static_cast<double>(1ULL << 53) * 2.0 - 1.0;
    }
};

}  // namespace

const char* to_string(ContactScenario s) noexcept {
    switch (s) {
        case ContactScenario::press: return "press";
        case ContactScenario::press_hard: return "press at the clamp";
        case ContactScenario::slide: return "slide";
        case ContactScenario::corner: return "corner (block task)";
        case ContactScenario::taps: return "taps";
        case ContactScenario::hard_taps: return "hard taps";
    }
    return "?";
}

namespace {

struct Setup {
    Scene scene;
    HandPath path;
    double seconds = 0.0;  // s
};

Setup setup_for(ContactScenario scenario, double stiffness, double seconds, double damping = 0.0) {
    Setup u{floor_scene(stiffness), {}, seconds};
    switch (scenario) {
        case ContactScenario::press: u.path = press_path(0.002, seconds); break;
        case ContactScenario::press_hard: u.path = press_path(0.006, seconds); break;
        case ContactScenario::slide: u.path = slide_path(seconds); break;
        case ContactScenario::taps: u.path = taps_path(seconds, 4.0, 0.003); break;
        case ContactScenario::hard_taps: u.path = taps_path(seconds, 5.0, 0.014); break;
        case ContactScenario::corner: {
            u.scene = block_scene();
            u.scene.force.stiffness = stiffness;
            BlockTaskParams bp;
            bp.finger_radius = u.scene.finger.radius;
            u.path = contour_block_task(bp);
            u.seconds = u.path.end();
            break;
        }
    }
    u.scene.force.law.damping = damping;
    return u;
}

}  // namespace

double declared_damping(ContactScenario scenario) {
    // The device declares the lowest damping over its hand path's box (sim_cld_device.cpp), so
    // each scenario's rig has its own.
    Setup u = setup_for(scenario, 1000.0, 1.0);
    return SimCldDevice(SimCldParams{}, std::move(u.path)).limits().damping;
}

ScenarioRun run_contact_scenario(ContactScenario scenario, double rate, double stiffness, const ScenarioOptions& opt) {
    SimCldParams sp;
    sp.hand.damping = opt.hand_damping;
    Setup u = setup_for(scenario, stiffness, opt.seconds, opt.damping);
    const double seconds = u.seconds;
    const Scene& scene = u.scene;
    HandPath path = std::move(u.path);
    ServoParams params;
    params.stiffness = stiffness;
    params.stiffness_slew = 1e9;  // K from the first tick: the probe is about K itself
    params.passivity = opt.passivity;
    SimRig rig(scene, std::move(path), rate, sp, params);
    ScenarioRun r;
    r.opened = rig.opened;
    if (!rig.opened) return r;
    r.b_declared = rig.device.limits().damping;
    Lcg rng{0x9E3779B97F4A7C15ULL ^ opt.seed};
    const double T = 1.0 / rate;  // s, nominal period
    double late_min = 1e9, late_max = -1e9;  // N
    double q3[2] = {1e9, -1e9}, q4[2] = {1e9, -1e9};  // N, min and max of |F| per quarter
    std::vector<double> late_t, late_f;  // s, N: |F| over the second half, for the ripple
    Vec2 last_force{0.0};  // N
    double step_sum = 0.0, force_sum = 0.0;  // N
    int late_contact = 0;
    DeviceReading reading;
    DeviceCommand command;
    ServoTick& servo = rig.servo;
    SimCldDevice& dev = rig.device;
    while (dev.time() < seconds) {
        // One tick as ServoLoop::step does it, with the period jittered: the device advances by
        // the actual period and the tick sees its clock.
        const bool ok = dev.read(reading);
        ServoInput in;
        in.t = reading.t;
        in.finger = reading.finger;
        in.phi = reading.phi;
        in.roller_l = reading.roller_l;
        in.device_fault = !ok || !reading.valid || dev.state() == DeviceState::fault;
        const ServoCommand& c = servo.tick(in);
        command.force = c.force;
        command.roller_drive = c.roller_drive;
        command.roller_target = c.roller_target;
        dev.write(command);
        dev.set_engaged(servo.state() == ServoState::engaged || servo.state() == ServoState::ramping);
        const double dt = T * (1.0 + opt.jitter * rng.uniform());

        const ServoSnapshot s = servo.snapshot();
        const double f = glm::length(s.force);  // N
        r.finite = r.finite && is_finite(s.force) && is_finite(s.finger);
        r.max_force = std::max(r.max_force, f);
        r.max_speed = std::max(r.max_speed, glm::length(dev.arm().velocity()));
        if (s.contact && r.contact_time < 0.0) r.contact_time = s.t;
        if (s.fault_count > 0 && !r.faulted) {
            r.faulted = true;
            r.fault = s.fault;
            r.cause = s.instability_cause;
            r.fault_time = s.t - std::max(0.0, r.contact_time);
        } else if (r.faulted) {
            r.max_force_after_fault = std::max(r.max_force_after_fault, f);
        }
        r.max_passivity_damping = std::max(r.max_passivity_damping, s.passivity_damping);
        if (s.t > seconds - 0.5) {
            late_min = std::min(late_min, f);
            late_max = std::max(late_max, f);
            if (s.contact) {
                step_sum += glm::length(s.force - last_force);
                force_sum += f;
                ++late_contact;
            }
        }
        last_force = s.force;
        if (s.t >= 0.5 * seconds) {
            double* q = s.t >= 0.75 * seconds ? q4 : q3;
            q[0] = std::min(q[0], f);
            q[1] = std::max(q[1], f);
            late_t.push_back(s.t);
            late_f.push_back(f);
        }
        if (r.b_normal == 0.0 && s.t >= 0.3) r.b_normal = dev.arm().cartesian_damping({0.0, 1.0});
        dev.advance(dt);
    }
    r.late_force_pp = late_max >= late_min ? late_max - late_min : 0.0;
    if (late_contact > 0) {
        r.late_mean_step = step_sum / late_contact;
        r.late_mean_force = force_sum / late_contact;
    }
    r.pp_third = q3[1] >= q3[0] ? q3[1] - q3[0] : 0.0;
    r.pp_fourth = q4[1] >= q4[0] ? q4[1] - q4[0] : 0.0;
    // The ripple about the force's 20 ms centred mean: what the hand's own motion makes the force
    // do (a stroke's 1 Hz swing, the hand-on-rig resonance near 9 Hz: averaged over 20 ms to within
    // 6 %) goes into the mean; an oscillation of the contact (tens of Hz and up: 40 Hz keeps 80 %
    // of its swing) and the encoders' steps stay in the deviation.
    const std::size_t n = late_f.size();
    const auto half = static_cast<std::size_t>(std::lround(0.010 * rate));  // ticks
    std::vector<double> prefix(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + late_f[i];
    double lo = 1e9, hi = -1e9;  // N
    for (std::size_t i = 0; i < n; ++i) {
        if (late_t[i] < 0.75 * seconds) continue;
        const std::size_t a = i >= half ? i - half : 0, b = std::min(n, i + half + 1);
        const double dev = late_f[i] - (prefix[b] - prefix[a]) / static_cast<double>(b - a);
        lo = std::min(lo, dev);
        hi = std::max(hi, dev);
    }
    r.ripple_fourth = hi >= lo ? hi - lo : 0.0;
    return r;
}

PassivityBounds passivity_bounds(double rate, ContactScenario scenario) {
    // A soft press (100 N/m, far below any bound) only to read the arm's damping along the normal.
    ScenarioOptions opt;
    opt.seconds = 0.4;
    const ScenarioRun probe = run_contact_scenario(ContactScenario::press, rate, 100.0, opt);
    return {2.0 * declared_damping(scenario) * rate, 2.0 * probe.b_normal * rate};
}

}  // namespace contactlab::drivers::sim
