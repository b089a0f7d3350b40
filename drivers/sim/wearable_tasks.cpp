// wearable_tasks.cpp — seed 003's step, bandwidth and curvature experiments on the simulated
// platform (see wearable_tasks.hpp).
#include "drivers/sim/wearable_tasks.hpp"

#include "haptics/stimuli.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace contactlab::drivers::sim {

using namespace contactlab::wearable;

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;

WearableSample sample_of(const WearableRig& rig) {
    WearableSample s;
    s.t = rig.time();
    s.reference = rig.force_reference();
    s.estimate = rig.estimate().tension;
    s.tension = rig.plant().tension();
    s.fault = is_fault(rig.output().status);
    return s;
}
}  // namespace

WearableStepResult wearable_step(const RigDef& def, const WearableStepDef& sd) {
    WearableRig rig(def);
    WearableStepResult out;
    const auto n = static_cast<long>(std::llround(sd.duration / sd.sample_period));
    for (long k = 0; k < n; ++k) {
        rig.command_force(rig.time() + 1e-12 >= sd.t_step ? Eigen::Vector3d::Constant(sd.step) : Eigen::Vector3d::Zero());
        rig.advance(sd.sample_period);
        out.samples.push_back(sample_of(rig));
        out.fault = out.fault || out.samples.back().fault;
    }
    // Per cable: first crossings of 10 % and 90 % of the step after it, mean over the window.
    for (int i = 0; i < 3; ++i) {
        double t10 = -1.0, t90 = -1.0, peak = 0.0, sum = 0.0;
        int count = 0;
        for (const WearableSample& s : out.samples) {
            if (s.t < sd.t_step) continue;
            const double q = s.estimate(i);
            if (t10 < 0.0 && q >= 0.1 * sd.step) t10 = s.t;
            if (t90 < 0.0 && q >= 0.9 * sd.step) t90 = s.t;
            peak = std::max(peak, q);
            if (s.t > sd.duration - sd.settle_window) {
                sum += q;
                ++count;
            }
        }
        const double rise = (t10 >= 0.0 && t90 >= 0.0) ? t90 - t10 : sd.duration;  // never reached: the run's length
        out.rise_time_s = std::max(out.rise_time_s, rise);
        if (count > 0) out.steady_error_pct = std::max(out.steady_error_pct, 100.0 * std::abs(sum / count - sd.step) / sd.step);
        out.overshoot_pct = std::max(out.overshoot_pct, 100.0 * (peak - sd.step) / sd.step);
    }
    return out;
}

WearableSineResponse wearable_sine(const RigDef& def, const WearableSineDef& sd, double freq,
                                   std::vector<WearableSample>* samples) {
    WearableRig rig(def);
    const double period = 1.0 / freq;
    const double settle = std::max(sd.settle_cycles * period, sd.min_settle);
    const double measure = sd.measure_cycles * period;
    const auto n_settle = static_cast<long>(std::llround(settle / sd.sample_period));
    const auto n_measure = static_cast<long>(std::llround(measure / sd.sample_period));
    const double w = kTwoPi * freq;
    Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
    double ref_a = 0.0, ref_b = 0.0;
    for (long k = 0; k < n_settle + n_measure; ++k) {
        const double t = rig.time();
        rig.command_force(Eigen::Vector3d::Constant(sd.offset + sd.amplitude * std::sin(w * t)));
        rig.advance(sd.sample_period);
        if (samples) samples->push_back(sample_of(rig));
        if (k >= n_settle) {
            // Fundamental by correlation over whole cycles, at the sample's time.
            const double ts = rig.time(), s = std::sin(w * ts), c = std::cos(w * ts);
            a += rig.estimate().tension * s;
            b += rig.estimate().tension * c;
            ref_a += s * s;
            ref_b += c * c;
        }
    }
    WearableSineResponse r;
    r.freq = freq;
    double gain = 0.0, phase = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double in_phase = a(i) / ref_a, quadrature = b(i) / ref_b;
        gain += std::hypot(in_phase, quadrature) / sd.amplitude / 3.0;
        phase += std::atan2(quadrature, in_phase) / 3.0;
    }
    r.gain = gain;
    r.phase = phase;
    return r;
}

WearableBandwidthResult wearable_bandwidth(const RigDef& def, const WearableSineDef& sd, double min_freq,
                                           double max_freq, int per_decade, double tolerance) {
    WearableBandwidthResult out;
    const double cutoff = 1.0 / std::sqrt(2.0);
    const int n = static_cast<int>(std::ceil(std::log10(max_freq / min_freq) * per_decade));
    double below = 0.0, above = 0.0;
    for (int k = 0; k <= n; ++k) {
        const double f = std::min(max_freq, min_freq * std::pow(10.0, static_cast<double>(k) / per_decade));
        out.sweep.push_back(wearable_sine(def, sd, f));
        if (out.sweep.back().gain < cutoff) {
            above = f;
            below = k > 0 ? out.sweep[out.sweep.size() - 2].freq : min_freq;
            out.found = true;
            break;
        }
    }
    if (out.found) {
        while (above - below > tolerance) {
            const double mid = 0.5 * (above + below);
            const WearableSineResponse r = wearable_sine(def, sd, mid);
            out.sweep.push_back(r);
            (r.gain < cutoff ? above : below) = mid;
        }
        out.bandwidth_hz = 0.5 * (above + below);
        std::sort(out.sweep.begin(), out.sweep.end(),
                  [](const WearableSineResponse& x, const WearableSineResponse& y) { return x.freq < y.freq; });
    }
    return out;
}

CurvatureArcResult curvature_arc(const RigDef& def, const CurvatureArcDef& cd) {
    if (!(std::isfinite(cd.chord) && cd.chord > 0.0) || !(std::isfinite(cd.height) && cd.height > 0.0 && cd.height <= 0.5 * cd.chord))
        throw std::invalid_argument("curvature arc: the height must lie in (0, chord / 2] and the chord be positive (m)");
    if (!(cd.speed > 0.0) || !(cd.contact_force >= 0.0) || !(cd.sample_period > 0.0))
        throw std::invalid_argument("curvature arc: speed, contact force and sample period must be positive");
    CurvatureArcResult out;
    out.radius = arc_cap_radius(cd.chord, cd.height);  // seed §4: r_a
    out.max_surface_angle = std::asin(0.5 * cd.chord / out.radius);
    WearableRig rig(def);
    const Pose rest = def.plant.platform.rest;
    const double kn = def.plant.stiffness(2, 2);  // N/m, the fingertip's normal stiffness
    const double travel = cd.chord + 2.0 * cd.margin;
    const double start = cd.reverse ? 0.5 * cd.chord + cd.margin : -0.5 * cd.chord - cd.margin;  // m, the contact's first x
    const double direction = cd.reverse ? -1.0 : 1.0;
    const auto n = static_cast<long>(std::ceil(travel / cd.speed / cd.sample_period));
    double sum2 = 0.0;
    int count = 0;
    double contact_start = -1.0;
    for (long k = 0; k <= n; ++k) {
        const double t = rig.time();
        CurvatureSample s;
        s.t = t;
        s.contact_x = start + direction * cd.speed * t;
        s.contact = std::abs(s.contact_x) <= 0.5 * cd.chord;
        // The arc's slope under the contact: y = sqrt(r^2 - x^2) - (r - h), dy/dx = -x / sqrt(r^2 - x^2).
        s.surface_angle = s.contact ? -std::asin(std::clamp(s.contact_x / out.radius, -1.0, 1.0)) : 0.0;
        Pose ref = rest;
        if (s.contact) {
            ref(2) += cd.contact_force / kn;  // press into the pad by F / k_n
            ref(3) = s.surface_angle;         // roll: the platform's y (along the finger) rises by it
        }
        rig.command_pose(ref);
        rig.advance(cd.sample_period);
        const Pose& xi = rig.plant().pose();
        s.platform_tilt = xi(3);
        s.tension = rig.plant().tension();
        s.platform_force = finger_wrench(def.plant.stiffness, rest, xi).head<3>().norm();
        s.fault = is_fault(rig.output().status);
        out.fault = out.fault || s.fault;
        if (s.contact && contact_start < 0.0) contact_start = t;
        if (s.contact && t - contact_start >= cd.settle) {
            const double e = s.platform_tilt - s.surface_angle;
            sum2 += e * e;
            ++count;
            out.tilt_max_error = std::max(out.tilt_max_error, std::abs(e));
        }
        out.samples.push_back(s);
    }
    out.tilt_rms = count > 0 ? std::sqrt(sum2 / count) : 0.0;
    return out;
}

}  // namespace contactlab::drivers::sim
