// bench_probes.cpp — closed-loop measurements on the simulated CLD rig (see bench_probes.hpp).
#include "drivers/sim/bench_probes.hpp"

#include "drivers/sim/roller_sine.hpp"
#include "drivers/sim/sim_rig.hpp"
#include "drivers/sim/stability_probes.hpp"
#include "drivers/tasks.hpp"
#include "haptics/servo_scene.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <utility>

namespace contactlab::drivers::sim {

namespace {
constexpr double kTwoPi = 6.283185307179586;
// Below this finger speed (m/s) nothing ran away: a 2 mm press moves the finger at cm/s at most,
// while a loop that the clamp did not hold would fling it at the arm's top speed.
constexpr double kRunawaySpeed = 1.0;
// Force ripple (N) under which a contact counts as settled whatever its trend: the quantisation
// limit cycle of a stable spring (K times a few encoder counts of ~20 um) stays below it.
constexpr double kSettledRipple = 0.1;
}  // namespace

PressResult press_floor(double stiffness, double rate, double hand_damping, double seconds, int arm_counts,
                        double joint_friction, bool limit_cycle) {
    SimCldParams sp;
    sp.arm.encoder_counts = arm_counts;
    sp.arm.friction = joint_friction;
    sp.hand.damping = hand_damping;
    const double R = 0.026;  // m, the finger's radius (SimCldParams' finger)
    HandPath path({{0.0, {0.0, R + 0.005}, 0.0}, {0.3, {0.0, R - 0.002}, 0.0}, {seconds, {0.0, R - 0.002}, 0.0}});
    const Scene scene = floor_scene(stiffness);
    ServoParams params;
    params.stiffness = stiffness;
    // The spring is at its value from the first tick (no slew): the probe is about K itself.
    params.stiffness_slew = 1e9;
    params.limit_cycle.enabled = limit_cycle;
    SimRig rig(scene, std::move(path), rate, sp, params);
    PressResult r;
    r.opened = rig.opened;
    if (!rig.opened) return r;
    r.b_declared = rig.device.limits().damping;
    const auto ticks = static_cast<long>(std::lround(seconds * rate));
    double fmin = 1e9, fmax = -1e9;
    double q3[2] = {1e9, -1e9}, q4[2] = {1e9, -1e9};  // N, min and max of f_y per quarter
    for (long k = 0; k < ticks; ++k) {
        rig.loop.step(1.0 / rate, true);
        const ServoSnapshot s = rig.servo.snapshot();
        r.finite = r.finite && is_finite(s.force) && is_finite(s.finger);
        r.max_force = std::max(r.max_force, glm::length(s.force));
        r.max_energy = std::max(r.max_energy, s.observer_energy);
        r.max_speed = std::max(r.max_speed, glm::length(rig.device.arm().velocity()));
        if (s.fault_count > 0 && !r.faulted) {
            r.faulted = true;
            r.fault = s.fault;
        }
        if (k > ticks - static_cast<long>(0.5 * rate)) {
            fmin = std::min(fmin, s.force.y);
            fmax = std::max(fmax, s.force.y);
        }
        if (k >= ticks / 2) {
            double* q = k >= 3 * ticks / 4 ? q4 : q3;
            q[0] = std::min(q[0], s.force.y);
            q[1] = std::max(q[1], s.force.y);
        }
        // Once pressed (the descent ends at 0.3 s): the damping the spring actually sees.
        if (k == static_cast<long>(0.3 * rate)) r.b_normal = rig.device.arm().cartesian_damping({0.0, 1.0});
    }
    r.late_force_pp = fmax - fmin;
    r.pp_third = q3[1] - q3[0];
    r.pp_fourth = q4[1] - q4[0];
    return r;
}

bool ripple_settled(double pp_third, double pp_fourth) {
    return pp_fourth < kSettledRipple || pp_fourth < 0.9 * pp_third;
}

double largest_stable_k(double rate, double lo, double hi, bool settled, bool ideal, double resolution) {
    return bisect_largest(lo, hi, resolution, [&](double k) {
        const PressResult r = ideal ? press_floor(k, rate, 0.0, 1.0, 1 << 24, 0.0, false) : press_floor(k, rate, 0.0, 1.0);
        // Settled: what oscillation is left is small, or dying out (a loop past the bound grows
        // into a limit cycle at the force clamp and stays there).
        return r.opened && !r.faulted && r.finite && r.max_speed < kRunawaySpeed &&
               (!settled || ripple_settled(r.pp_third, r.pp_fourth));
    });
}

DamperResponse damper_response(double damping, double rate) {
    const double T = 1.0 / rate;  // s
    const double K = 100.0;       // N/m: soft, so the spring's part stays far under the clamp
    const double d1 = 0.002, d2 = 0.00201;  // m, depths: held, then 10 um deeper in one tick
    Scene scene = floor_scene(K);
    scene.force.law.damping = damping;
    ServoConfig config;
    config.period = T;
    config.has_roller = false;
    ServoParams params;
    params.stiffness = K;
    params.stiffness_slew = 1e9;
    params.safety.watchdog_timeout = SimRig::watchdog_for(rate);
    ServoTick servo(config, params);
    servo.scenes().publish(std::make_unique<ServoScene>(scene));
    servo.connect(0.0);
    const double R = scene.finger.radius;  // m
    // Free space; first contact (a contact's first tick has no previous depth: no damping); held
    // at d1; moved to d2; held at d2.
    const double ys[] = {R + 0.005, R - d1, R - d1, R - d2, R - d2};
    double damper[5] = {};  // N along the normal (+y): the force less the spring's K d
    for (int k = 0; k < 5; ++k) {
        ServoInput in;
        in.t = k * T;
        in.finger = {0.0, ys[k]};
        servo.tick(in);
        damper[k] = servo.snapshot().rendered_force.y - K * (R - ys[k]);
    }
    return {damper[3] * T / (d2 - d1), damper[4]};
}

double effective_damping(double damping, double rate) { return damper_response(damping, rate).applied; }

ZWidthRow zwidth_row(double rate, double damping, double resolution) {
    ZWidthRow row;
    row.rate_hz = rate;
    row.damping = damping;
    row.resolution = resolution;
    row.damping_applied = effective_damping(damping, rate);
    // The arm's damping along the normal and the declared one, read as the stability table does.
    const PressResult probe = press_floor(100.0, rate, 0.0, 0.4);
    row.b_normal = probe.b_normal;
    row.b_declared = probe.b_declared;
    row.bound_normal = 2.0 * (row.b_normal - std::abs(row.damping_applied)) * rate;
    row.bound_declared = 2.0 * (row.b_declared - std::abs(row.damping_applied)) * rate;
    // The stability table's bracket at this rate, so that at B = 0 the press repeats its bisection.
    row.search_lo = 0.05 * 2.0 * row.b_normal * rate;
    row.search_hi = 4.0 * 2.0 * row.b_normal * rate;
    auto largest = [&](ContactScenario scenario, bool settled) {
        return bisect_largest(row.search_lo, row.search_hi, resolution, [&](double k) {
            ScenarioOptions opt;
            opt.seconds = 1.0;
            opt.damping = damping;
            const ScenarioRun r = run_contact_scenario(scenario, rate, k, opt);
            // Settled: held still, the stability table's test on |F| itself; sliding, the force
            // follows the stroke, so the ripple about its 20 ms mean, and only its size (the last
            // quarter's stroke is not the third's: a smaller ripple would not mean a dying one).
            const bool calm = scenario == ContactScenario::press ? ripple_settled(r.pp_third, r.pp_fourth)
                                                                 : r.ripple_fourth < kSettledRipple;
            return r.opened && !r.faulted && r.finite && r.max_speed < kRunawaySpeed && (!settled || calm);
        });
    };
    row.k_press = largest(ContactScenario::press, true);
    row.k_slide = largest(ContactScenario::slide, true);
    row.k_press_no_fault = largest(ContactScenario::press, false);
    row.k_slide_no_fault = largest(ContactScenario::slide, false);
    return row;
}

StabilityRow stability_row(double rate, double resolution) {
    StabilityRow row;
    row.rate_hz = rate;
    row.resolution = resolution;
    // A soft press (100 N/m, far below any bound) only to read the arm's damping along the normal.
    const PressResult probe = press_floor(100.0, rate, 0.0, 0.4);
    row.b_normal = probe.b_normal;
    row.passivity_bound = 2.0 * probe.b_normal / (1.0 / rate);  // N/m: 2 b / T, T = 1 / rate
    // The bracket: well inside (0.05x, where even the rig at 20 kHz settles: K x one 18 um count
    // is 0.06 N there) to far past (4x) the bound, so
    // both the observer's report and the settling limit land inside it.
    row.search_lo = 0.05 * row.passivity_bound;
    row.search_hi = 4.0 * row.passivity_bound;
    row.k_no_fault = largest_stable_k(rate, row.search_lo, row.search_hi, false, false, resolution);
    row.k_settles = largest_stable_k(rate, row.search_lo, row.search_hi, true, false, resolution);
    row.k_ideal_no_fault = largest_stable_k(rate, row.search_lo, row.search_hi, false, true, resolution);
    row.k_ideal_settles = largest_stable_k(rate, row.search_lo, row.search_hi, true, true, resolution);
    row.b_declared = probe.b_declared;
    row.bound_declared = 2.0 * probe.b_declared * rate;
    for (int i = 0; i < 4; ++i) row.above[i] = above_bound_probe(rate, kAboveBoundRatios[i]);
    return row;
}

AboveBoundProbe above_bound_probe(double rate, double ratio, double seconds) {
    const PassivityBounds bounds = passivity_bounds(rate, ContactScenario::press);
    ScenarioOptions opt;
    opt.seconds = seconds;
    const ScenarioRun r = run_contact_scenario(ContactScenario::press, rate, ratio * bounds.normal, opt);
    AboveBoundProbe p;
    p.ratio = ratio;
    p.max_force = r.max_force;
    const bool bounded = r.opened && r.finite && r.max_force <= 1.5 + 1e-9 && r.max_speed < kRunawaySpeed;
    if (r.faulted && r.fault == ServoFault::instability) {
        p.outcome = AboveBoundOutcome::detected;
        p.detect_time = r.fault_time;
        p.cause = r.cause;
    } else if (!bounded) {
        p.outcome = AboveBoundOutcome::runaway;
    } else {
        p.outcome = r.late_force_pp < kSettledRipple ? AboveBoundOutcome::at_rest : AboveBoundOutcome::bounded_bounce;
    }
    return p;
}

BlockTracking block_task_tracking(double speed, double rate, const RollerGains& gains, double stiffness,
                                  const SimCldParams& sp) {
    Scene scene = block_scene();
    if (stiffness > 0.0) scene.force.stiffness = stiffness;
    BlockTaskParams bp;
    bp.finger_radius = scene.finger.radius;
    bp.speed = speed;
    ServoParams params;
    params.roller = gains;
    SimRig rig(scene, contour_block_task(bp), rate, sp, params);
    BlockTracking tr;
    tr.opened = rig.opened;
    if (!rig.opened) return tr;
    double lmin = 1e9, lmax = -1e9;  // m
    double sum_sq = 0.0;             // m^2
    const double T = 1.0 / rate;     // s
    // 10 ms windows for the target's rate: l_d = -R phi moves in angle-encoder steps of 0.04 mm,
    // which a per-tick difference would report as bursts of metres per second.
    const auto window = std::max<std::size_t>(2, static_cast<std::size_t>(std::lround(0.010 * rate)));
    std::deque<double> recent;       // m, the last `window` targets while engaged in contact
    const auto ticks = static_cast<std::uint64_t>(std::lround(rig.device.hand().path().end() * rate));
    // The whole run, for the jump analysis afterwards (it looks kJumpRateWindow ahead).
    std::vector<double> target(ticks, 0.0), measured(ticks, 0.0);  // m
    std::vector<char> sampled(ticks, 0);                             // engaged and in contact
    // What the finger feels: the same proxy code (a second ServoScene of the same scene) fed the
    // simulated finger's true pose (arm endpoint and finger angle before the encoders) gives the
    // true contact location, against which the element (after the wires) is compared. Both are
    // taken at the instant the servo's read samples, so the only difference from `target` is the
    // encoders' quantisation.
    ServoScene truth(scene);
    const RollerTravel travel = rig.servo.config().roller_travel;  // params.roller_travel = 0: all of it
    std::vector<double> true_target(ticks, 0.0), element(ticks, 0.0);  // m
    std::vector<char> true_contact(ticks, 0);
    for (std::uint64_t k = 0; k < ticks; ++k) {
        const Vec2 finger_true = rig.device.arm().endpoint();  // m, unquantised
        const double phi_true = rig.device.hand().phi();       // rad, unquantised
        element[k] = rig.device.roller().element();            // m
        rig.loop.step(T, true);
        const ServoSnapshot s = rig.servo.snapshot();
        // Every tick, as the servo's own proxy (its history is the point); first tick: reset at the
        // finger, as ServoTick::swap_scene does for a first scene.
        if (k == 0) truth.proxy.reset(finger_true, phi_true);
        ProxyDef def = truth.proxy.def();
        def.stiffness = s.stiffness;
        def.max_force = s.max_force;
        truth.proxy.set_def(def);
        const ProxyOutput& o = truth.proxy.update(finger_true, phi_true);
        true_target[k] = std::clamp(o.l_d, travel.min, travel.max);
        true_contact[k] = o.contact ? 1 : 0;
        // In free space l_d is the anticipation's and the roller is not felt: only contact counts.
        if (s.state != ServoState::engaged || !s.contact) {
            recent.clear();
            continue;
        }
        sampled[k] = 1;
        target[k] = s.roller_target;
        measured[k] = s.roller_l;
        lmin = std::min(lmin, s.roller_target);
        lmax = std::max(lmax, s.roller_target);
        const double e = s.roller_target - s.roller_l;  // m
        tr.max_measured = std::max(tr.max_measured, std::abs(e));
        sum_sq += e * e;
        ++tr.samples;
        tr.max_element = std::max(tr.max_element, std::abs(s.roller_target - rig.device.roller().element()));
        recent.push_back(s.roller_target);
        if (recent.size() > window) {
            recent.pop_front();
            tr.max_rate = std::max(tr.max_rate, std::abs(recent.back() - recent.front()) / (window - 1) * rate);
        }
    }
    tr.l_range = tr.samples > 0 ? lmax - lmin : 0.0;
    tr.rms_measured = tr.samples > 0 ? std::sqrt(sum_sq / static_cast<double>(tr.samples)) : 0.0;

    // Jumps of l_d (bench_probes.hpp, RollerTrackingRow): compare the mean rate over the window
    // before each tick with that over the window after it.
    const auto n = static_cast<std::int64_t>(ticks);
    const auto w = static_cast<std::int64_t>(std::max(1L, std::lround(kJumpRateWindow * rate)));     // ticks
    const auto settle = static_cast<std::int64_t>(std::lround(kJumpSettleWindow * rate));            // ticks
    std::vector<char> jump(ticks, 0);
    for (std::int64_t k = 0; k < n; ++k) {
        if (!sampled[k]) continue;
        bool all_in = k >= w && k + w < n;
        for (std::int64_t j = k - w; all_in && j <= k + w; ++j) all_in = sampled[j] != 0;
        if (!all_in) {
            jump[k] = 1;  // contact made or lost nearby: l_d switches from or to the anticipation's
            continue;
        }
        const double before = (target[k] - target[k - w]) / (w * T);  // m/s
        const double after = (target[k + w] - target[k]) / (w * T);    // m/s
        jump[k] = std::abs(after - before) > kJumpRateChange;
    }
    double track_sq = 0.0, true_sq = 0.0;  // m^2
    std::int64_t since_jump = settle + 1;  // ticks since the last jump tick
    for (std::int64_t k = 0; k < n; ++k) {
        if (jump[k] && (k == 0 || !jump[k - 1])) ++tr.jumps;
        since_jump = jump[k] ? 0 : since_jump + 1;
        if (!sampled[k]) continue;
        const double e = std::abs(target[k] - measured[k]);  // m
        if (since_jump <= settle) {
            tr.max_jump = std::max(tr.max_jump, e);
        } else {
            tr.max_tracking = std::max(tr.max_tracking, e);
            track_sq += e * e;
            ++tr.tracking_samples;
            // The true measure over the same ticks (the jumps are l_d's, found on the target the
            // servo had); the true proxy is in contact there too unless the finger grazes an edge
            // within an encoder count of it, which is a jump's window anyway.
            if (!true_contact[k]) continue;
            const double et = std::abs(true_target[k] - element[k]);  // m
            tr.max_true_tracking = std::max(tr.max_true_tracking, et);
            true_sq += et * et;
            ++tr.true_samples;
            tr.max_staircase = std::max(tr.max_staircase, std::abs(target[k] - true_target[k]));
            tr.max_true_encoder = std::max(tr.max_true_encoder, std::abs(true_target[k] - measured[k]));
            tr.max_wire = std::max(tr.max_wire, std::abs(element[k] - measured[k]));
        }
    }
    tr.rms_tracking = tr.tracking_samples > 0 ? std::sqrt(track_sq / static_cast<double>(tr.tracking_samples)) : 0.0;
    tr.rms_true_tracking = tr.true_samples > 0 ? std::sqrt(true_sq / static_cast<double>(tr.true_samples)) : 0.0;
    return tr;
}

double onset_floor(double v, double T, const RollerParams& p) {
    const double n = kTwoPi / p.lead;                                    // rad/m
    const double mass = p.rotor_inertia * n * n + p.nut_mass;            // kg
    const double stall = p.torque_constant * n * p.max_voltage / p.resistance;  // N
    const double a_max = (stall - p.coulomb) / mass;                     // m/s^2
    return v * T + v * v / (2.0 * a_max);
}

RollerGains roller_gains_scaled(double scale, const RollerParams& plant) {
    // Small-signal plant l / V = g / (s (tau s + 1)): g = 1 / (k_e 2 pi / lead), m/(V s).
    const double g = 1.0 / (plant.torque_constant * kTwoPi / plant.lead);
    RollerGains out;
    out.kp *= scale * scale;
    out.ki *= scale * scale * scale;
    // Kd(s p0) = (3 tau s p0 - 1) / g = s (3 tau p0 - 1) / g + (s - 1) / g.
    out.kd = out.kd * scale + (scale - 1.0) / g;
    // The feed-forward cancels Kd + back-EMF = 3 tau p / g, which scales with p.
    out.kff *= scale;
    // Used as placed: the table explores the gains themselves (p T = 0.8 at scale 2 and 1 kHz),
    // which the controller's re-placement near the sampling (RollerGains::pole) would undo.
    out.pole = 0.0;
    return out;
}

}  // namespace contactlab::drivers::sim

namespace contactlab {

const char* to_string(AboveBoundOutcome o) noexcept {
    switch (o) {
        case AboveBoundOutcome::detected: return "detected";
        case AboveBoundOutcome::bounded_bounce: return "bounded bounce";
        case AboveBoundOutcome::at_rest: return "at rest";
        case AboveBoundOutcome::runaway: return "runaway";
    }
    return "?";
}

std::vector<StabilityRow> stability_table(bool quick) {
    // quick keeps 250 Hz and 1 kHz and drops 4-20 kHz, the costly rates (1 s of virtual time is
    // 4000-20000 ticks of 10 arm sub-steps, per bisection step), and keeps the 2 % bisection: its rows are the full
    // table's, number for number, and a coarser stop would cost little time but eat into the
    // margin of the ideal arm's settling limit (0.80 x 2b/T at 250 Hz) over the 0.75 the tests
    // hold it to.
    const std::vector<double> rates = quick ? std::vector<double>{250.0, 1000.0}
                                            : std::vector<double>{100.0, 250.0, 1000.0, 4000.0, 10000.0, 20000.0};
    const double resolution = 1.02;
    std::vector<StabilityRow> rows;
    rows.reserve(rates.size());
    for (double rate : rates) rows.push_back(drivers::sim::stability_row(rate, resolution));
    return rows;
}

std::vector<ZWidthRow> zwidth_table(bool quick) {
    // N s/m. Full: finer where the passivity bound falls to 0 (B = b, 1.1-1.7 N s/m here), then on
    // to 5. Quick keeps what shows the shape at 1 kHz (B = 0 for the stability table's figure, the
    // fall of the settled K, and past b) and three at 10 kHz, where a bisection costs ten times as
    // many ticks: 10 kHz rows are ~85 % of the table's time.
    const std::vector<double> full = {0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 5.0};
    const std::vector<std::pair<double, std::vector<double>>> plan =
        quick ? std::vector<std::pair<double, std::vector<double>>>{{1000.0, {0.0, 0.5, 1.0, 2.0, 5.0}},
                                                                    {10000.0, {0.0, 1.0, 2.0}}}
              : std::vector<std::pair<double, std::vector<double>>>{{1000.0, full}, {10000.0, full}};
    std::vector<ZWidthRow> rows;
    for (const auto& [rate, dampings] : plan)
        for (const double b : dampings) rows.push_back(drivers::sim::zwidth_row(rate, b));
    return rows;
}

std::vector<RollerTrackingRow> roller_tracking_table(bool quick) {
    const std::vector<double> scales = quick ? std::vector<double>{1.0, 2.0} : std::vector<double>{0.5, 1.0, 2.0};
    // m/s; quick skips 1 cm/s (an 18 s task) and 10 cm/s.
    const std::vector<double> speeds = quick ? std::vector<double>{0.02, 0.05}
                                             : std::vector<double>{0.01, 0.02, 0.05, 0.1};
    const double rate = 1000.0;  // Hz: seed 000's servo rate
    std::vector<RollerTrackingRow> rows;
    rows.reserve((scales.size() + 1) * speeds.size());
    auto run = [&](double scale, bool feed_forward) {
        RollerGains gains = drivers::sim::roller_gains_scaled(scale);
        if (!feed_forward) gains.kff = 0.0;
        for (double speed : speeds) {
            const drivers::sim::BlockTracking tr = drivers::sim::block_task_tracking(speed, rate, gains);
            const double nan = std::numeric_limits<double>::quiet_NaN();
            RollerTrackingRow row;
            row.gain_scale = scale;
            row.finger_speed = speed;
            row.rate_hz = rate;
            row.feed_forward = feed_forward;
            row.max_error = tr.opened ? tr.max_measured : nan;
            row.rms_error = tr.opened ? tr.rms_measured : nan;
            row.max_tracking_error = tr.opened && tr.tracking_samples > 0 ? tr.max_tracking : nan;
            row.rms_tracking_error = tr.opened && tr.tracking_samples > 0 ? tr.rms_tracking : nan;
            row.max_jump_error = tr.opened ? tr.max_jump : nan;
            row.jumps = tr.jumps;
            const bool truth = tr.opened && tr.true_samples > 0;
            row.max_true_tracking_error = truth ? tr.max_true_tracking : nan;
            row.rms_true_tracking_error = truth ? tr.rms_true_tracking : nan;
            row.max_target_staircase = truth ? tr.max_staircase : nan;
            row.max_true_encoder_error = truth ? tr.max_true_encoder : nan;
            row.pole_rad_s = 400.0 * scale;
            row.max_element_error = tr.max_element;
            row.target_range = tr.l_range;
            row.max_target_rate = tr.max_rate;
            row.onset_floor = drivers::sim::onset_floor(tr.max_rate, 1.0 / rate);
            rows.push_back(row);
        }
    };
    for (double scale : scales) run(scale, true);
    run(1.0, false);  // the "before": seed 000's eq. 2 alone, at the default poles
    return rows;
}

std::vector<RollerJumpRow> roller_jump_table(bool quick) {
    const drivers::sim::SimCldParams sp;
    // m: (from, to); the 16 mm jump ends 2 mm inside the +10 mm stop.
    const std::vector<std::pair<double, double>> jumps =
        quick ? std::vector<std::pair<double, double>>{{-0.005, 0.005}}
              : std::vector<std::pair<double, double>>{{0.0, 0.002}, {-0.005, 0.005}, {-0.008, 0.008}};
    std::vector<RollerJumpRow> rows;
    for (const auto& [from, to] : jumps) {
        const drivers::sim::RollerJumpResponse r =
            drivers::sim::roller_jump_response(sp.roller, RollerGains{}, from, to, 1000.0, 0.05e-3, 0.5, sp.substep,
                                               sp.min_substeps);
        RollerJumpRow row;
        row.jump = r.jump;
        row.jump_settle_s = r.finite ? r.settle_s : std::numeric_limits<double>::quiet_NaN();
        row.force_limited_s = r.force_limited_s;
        row.band = r.band;
        row.overshoot = r.overshoot;
        row.max_excursion = r.max_excursion;
        row.half_travel = r.half_travel;
        rows.push_back(row);
    }
    return rows;
}

double roller_bandwidth_hz(bool quick) {
    const drivers::sim::SimCldParams sp;
    drivers::sim::SineTest st;  // 1 kHz, 5 mm amplitude = 1.0 cm peak to peak
    // Integrate the roller exactly as the simulated CLD device does.
    st.substep = sp.substep;
    st.min_substeps = sp.min_substeps;
    // The low end of the sweep is what costs (settle + measure cycles at 0.5 Hz are 20 s of
    // virtual time); the -3 dB point of this motor on a 1 cm sine is several Hz, so quick starts
    // at 2 Hz and stops the bisection at 0.05 Hz.
    const drivers::sim::BandwidthResult bw =
        quick ? drivers::sim::roller_bandwidth(sp.roller, RollerGains{}, st, 2.0, 100.0, 12, 0.05)
              : drivers::sim::roller_bandwidth(sp.roller, RollerGains{}, st);
    return bw.found ? bw.bandwidth : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace contactlab
