// roller_sine.cpp — sine response and bandwidth of the simulated CLD roller (see roller_sine.hpp).
#include "drivers/sim/roller_sine.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::drivers::sim {

namespace {
constexpr double kTwoPi = 6.283185307179586;
}

SineResponse roller_sine_response(const RollerParams& plant, const RollerGains& gains, const SineTest& test,
                                  double freq) {
    CldRoller roller(plant);
    roller.place_at(0.0);
    const double half = test.travel > 0.0 ? std::min(0.5 * test.travel, roller.half_travel()) : roller.half_travel();
    RollerController ctl(gains, RollerTravel{-half, half});
    ctl.reset(roller.measured());
    const double T = 1.0 / test.rate;  // s
    const int n_sub = std::max(std::max(1, test.min_substeps), static_cast<int>(std::ceil(T / test.substep - 1e-9)));
    const double h = T / n_sub;        // s
    // Whole ticks per measured window; the window is rounded to whole ticks, and the fundamental
    // is projected on the exact sine and cosine of those tick times (a small leakage only).
    const auto settle = static_cast<long>(std::lround(test.settle_cycles / freq * test.rate));
    const auto measure = static_cast<long>(std::lround(test.measure_cycles / freq * test.rate));
    double s_l = 0, c_l = 0, s_e = 0, c_e = 0, ss = 0, cc = 0, sc = 0;
    SineResponse r;
    r.freq = freq;
    for (long k = 0; k < settle + measure; ++k) {
        const double t = k * T;                              // s
        const double w = kTwoPi * freq * t;                  // rad
        const double ld = test.amplitude * std::sin(w);      // m
        const double l = roller.measured();                  // m
        const double e = roller.element();                   // m
        roller.set_voltage(ctl.step(ld, l, T));
        if (k >= settle) {
            const double sn = std::sin(w), cs = std::cos(w);
            s_l += l * sn;
            c_l += l * cs;
            s_e += e * sn;
            c_e += e * cs;
            ss += sn * sn;
            cc += cs * cs;
            sc += sn * cs;
            r.max_error = std::max(r.max_error, std::abs(ld - l));
        }
        for (int i = 0; i < n_sub; ++i) roller.step(h);
    }
    // Least squares for y = a sin + b cos over the samples (2x2 normal equations).
    const double det = ss * cc - sc * sc;
    auto fit = [&](double sy, double cy, double& a, double& b) {
        a = (sy * cc - cy * sc) / det;
        b = (cy * ss - sy * sc) / det;
    };
    double a, b;
    fit(s_l, c_l, a, b);
    r.gain = std::hypot(a, b) / test.amplitude;
    r.phase = std::atan2(b, a);
    fit(s_e, c_e, a, b);
    r.element_gain = std::hypot(a, b) / test.amplitude;
    return r;
}

BandwidthResult roller_bandwidth(const RollerParams& plant, const RollerGains& gains, const SineTest& test,
                                 double min_freq, double max_freq, int per_decade, double tolerance) {
    BandwidthResult out;
    const double target = 1.0 / std::sqrt(2.0);  // -3 dB
    const int n = std::max(2, static_cast<int>(std::ceil(std::log10(max_freq / min_freq) * per_decade)) + 1);
    double lo = 0.0, hi = 0.0;
    for (int i = 0; i < n; ++i) {
        const double f = min_freq * std::pow(max_freq / min_freq, static_cast<double>(i) / (n - 1));
        const SineResponse r = roller_sine_response(plant, gains, test, f);
        out.sweep.push_back(r);
        if (r.gain < target) {
            hi = f;
            lo = i > 0 ? out.sweep[i - 1].freq : f;
            out.found = i > 0;
            break;
        }
    }
    if (!out.found) return out;
    while (hi - lo > tolerance) {
        const double mid = 0.5 * (lo + hi);
        const SineResponse r = roller_sine_response(plant, gains, test, mid);
        out.sweep.push_back(r);
        (r.gain < target ? hi : lo) = mid;
    }
    out.bandwidth = 0.5 * (lo + hi);
    std::sort(out.sweep.begin(), out.sweep.end(),
              [](const SineResponse& x, const SineResponse& y) { return x.freq < y.freq; });
    return out;
}

RollerStepRun roller_step_run(const RollerParams& plant, const RollerGains& gains, double rate, double hold,
                              double substep, int min_substeps) {
    CldRoller roller(plant);
    roller.place_at(0.0);
    RollerController ctl(gains, RollerTravel{-roller.half_travel(), roller.half_travel()});
    ctl.reset(roller.measured());
    const double T = 1.0 / rate;  // s
    const int n_sub = std::max(std::max(1, min_substeps), static_cast<int>(std::ceil(T / substep - 1e-9)));
    const double h = T / n_sub;   // s
    const double steps[] = {0.008, -0.008, 0.002, 0.0};  // m
    const double t_steps = 4 * hold;                      // s
    const double t_end = t_steps + 1.0;                   // s
    RollerStepRun r;
    double prev_target = 0.0;  // m
    double step_dir = 0.0;     // sign of the current step
    for (long k = 0; k * T < t_end; ++k) {
        const double t = k * T;  // s
        double target = 0.0;     // m
        if (t < t_steps) {
            const int i = std::min(3, static_cast<int>(t / hold));
            target = steps[i];
            if (target != prev_target) step_dir = target > prev_target ? 1.0 : -1.0;
        } else {
            target = 0.005 * std::sin(kTwoPi * 5.0 * (t - t_steps));
            step_dir = 0.0;
        }
        prev_target = target;
        const double l = roller.measured();  // m
        const double u = ctl.step(target, l, T);
        roller.set_voltage(u);
        r.finite = r.finite && std::isfinite(u) && std::isfinite(l) && std::isfinite(roller.element());
        r.max_drive = std::max(r.max_drive, std::abs(u));
        const double e = target - l;  // m
        if (t < t_steps) {
            if (std::fmod(t, hold) > 0.8 * hold) r.max_settle_error = std::max(r.max_settle_error, std::abs(e));
            r.max_overshoot = std::max(r.max_overshoot, -step_dir * e);
        } else if (t > t_end - 0.5) {
            r.max_sine_error = std::max(r.max_sine_error, std::abs(e));
        }
        for (int i = 0; i < n_sub; ++i) roller.step(h);
        r.max_nut = std::max(r.max_nut, std::abs(roller.nut()));
    }
    return r;
}

RollerJumpResponse roller_jump_response(const RollerParams& plant, const RollerGains& gains, double from, double to,
                                        double rate, double band, double hold, double substep, int min_substeps) {
    CldRoller roller(plant);
    roller.place_at(from);
    RollerController ctl(gains, RollerTravel{-roller.half_travel(), roller.half_travel()});
    ctl.reset(roller.measured());
    const double T = 1.0 / rate;  // s
    const int n_sub = std::max(std::max(1, min_substeps), static_cast<int>(std::ceil(T / substep - 1e-9)));
    const double h = T / n_sub;   // s
    RollerJumpResponse r;
    r.jump = to - from;
    r.band = band;
    r.half_travel = roller.half_travel();
    r.force_limited_s = force_limited_jump_time(plant, r.jump);
    const double dir = r.jump >= 0.0 ? 1.0 : -1.0;
    double last_out = 0.0;  // s, the end of the last tick outside the band
    const auto ticks = static_cast<long>(std::lround(hold * rate));
    for (long k = 0; k < ticks; ++k) {
        const double l = roller.measured();  // m
        const double u = ctl.step(to, l, T);
        roller.set_voltage(u);
        r.finite = r.finite && std::isfinite(u) && std::isfinite(l);
        const double e = to - l;  // m
        // Tick k reads the roller at k T (the jump is seen at k = 0).
        if (std::abs(e) > band) last_out = (k + 1) * T;
        r.overshoot = std::max(r.overshoot, -dir * e);
        for (int i = 0; i < n_sub; ++i) roller.step(h);
        r.max_excursion = std::max(r.max_excursion, std::abs(roller.nut()));
    }
    r.settle_s = last_out;
    return r;
}

double force_limited_jump_time(const RollerParams& plant, double jump) {
    const double d = std::abs(jump);  // m
    if (!(d > 0.0)) return 0.0;
    constexpr double h = 1e-5;        // s
    // Full drive toward the target until `ts` (s), then full drive back until the nut turns:
    // returns how far it got (m) and when it stopped (s).
    auto run = [&](double ts, double& t_stop) {
        CldRoller r(plant);
        r.place_at(-0.5 * d);  // centred, so even a full-travel jump stays off the stops
        double t = 0.0, prev = r.nut();
        while (t < 1.0) {
            r.set_voltage(t < ts ? plant.max_voltage : -plant.max_voltage);
            r.step(h);
            t += h;
            if (t > ts && r.nut() <= prev) break;
            prev = r.nut();
        }
        t_stop = t;
        return prev + 0.5 * d;
    };
    double lo = 0.0, hi = 0.5, t_stop = 0.0;  // s: the switch time lies between
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (run(mid, t_stop) < d ? lo : hi) = mid;
    }
    run(hi, t_stop);
    return t_stop;
}

}  // namespace contactlab::drivers::sim
