// hand_path.hpp — the scripted hand's intended path: samples (t, x, y, phi), linearly
// interpolated; read from a CSV with the header `t,x,y,phi` (s, m, m, rad), or generated.
#pragma once

#include "haptics/vec2.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace contactlab::drivers {

struct PathSample {
    double t = 0.0;    // s
    Vec2 x{0.0};       // m, intended finger centre
    double phi = 0.0;  // rad
};

// A bad path file; the message names the file, line and column.
struct HandPathError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct PathPoint {
    Vec2 x{0.0};       // m
    Vec2 v{0.0};       // m/s, slope of the segment in use
    double phi = 0.0;  // rad
};

class HandPath {
public:
    HandPath() = default;
    // Times must strictly increase; at least one sample.
    explicit HandPath(std::vector<PathSample> samples);

    // One interval of the path, from a sample to the next: at() and phi_at() of a time t it holds
    // are the path's own, the same bits, without the cursor's search and the path's end checks.
    // A simulated rig finds the interval its servo tick starts in (interval_at) and asks it for
    // its ten substeps' hand (two asks a substep, the search most of their cost before). It keeps
    // the interval's numbers, not references to the path.
    class Interval {
    public:
        Interval() = default;  // holds no time
        // The differences are taken here once, as at() took them each call: the same bits.
        Interval(const PathSample& a, const PathSample& b, Vec2 slope, bool first) noexcept
            : lo_(first ? std::nextafter(a.t, b.t) : a.t), hi_(b.t), t0_(a.t), span_(b.t - a.t), x0_(a.x), dx_(b.x - a.x),
              slope_(slope), phi0_(a.phi), dphi_(b.phi - a.phi) {}
        // Whether t (s) lies in it: [a.t, b.t), and after a.t where a is the path's first sample
        // (the path holds that one). False for NaN.
        bool holds(double t) const noexcept { return t >= lo_ && t < hi_; }
        PathPoint at(double t) const noexcept {
            const double u = fraction(t);
            return {x0_ + dx_ * u, slope_, phi0_ + dphi_ * u};
        }
        double phi_at(double t) const noexcept { return phi0_ + dphi_ * fraction(t); }

    private:
        double fraction(double t) const noexcept { return (t - t0_) / span_; }
        double lo_ = std::numeric_limits<double>::infinity(), hi_ = -std::numeric_limits<double>::infinity();  // s
        double t0_ = 0.0, span_ = 1.0;  // s: a.t, b.t - a.t
        Vec2 x0_{0.0}, dx_{0.0};        // m: a.x, b.x - a.x
        Vec2 slope_{0.0};               // m/s
        double phi0_ = 0.0, dphi_ = 0.0;  // rad: a.phi, b.phi - a.phi
    };

    // Linear interpolation; before the first sample holds the first, after the last holds the
    // last (with zero velocity). Amortised O(1) for increasing t (a cursor), no allocation.
    // Inline, like locate(): a simulated rig asks often, and the calls themselves were a good
    // part of it.
    PathPoint at(double t) const noexcept {
        if (samples_.empty()) return {};
        if (!locate(t)) {
            const PathSample& s = held(t);
            return {s.x, Vec2{0.0}, s.phi};
        }
        return interval(cursor_).at(t);
    }
    // at(t).phi alone, the same bits (a simulated finger's angle asks for it every substep).
    double phi_at(double t) const noexcept {
        if (samples_.empty()) return 0.0;
        if (!locate(t)) return held(t).phi;
        return interval(cursor_).phi_at(t);
    }
    // The interval t (s) lies in, or one that holds no time where the path holds a sample there
    // (before its first sample, at or after its last).
    Interval interval_at(double t) const noexcept { return locate(t) ? interval(cursor_) : Interval{}; }
    // A hand that steers by feel (a closed loop, not a script) writes its path as it goes: one
    // sample after the last (its t later than the last's), amortised O(1). Reserve what a trial
    // needs first to keep the servo-rate appends free of reallocation.
    void append(const PathSample& s);
    void reserve(std::size_t n) {
        samples_.reserve(n);
        slopes_.reserve(n);
    }
    double start() const { return samples_.front().t; }
    double end() const { return samples_.back().t; }
    const std::vector<PathSample>& samples() const { return samples_; }

private:
    // Puts the cursor on the interval [t0, t1) at or before t; false (the cursor untouched)
    // outside the path, which at() and phi_at() hold.
    bool locate(double t) const noexcept {
        const std::size_t n = samples_.size();
        if (n == 0 || !(t > samples_.front().t) || t >= samples_.back().t) return false;
        // The interval is the last sample at or before t (and before the last sample): found from the
        // cursor, stepping back or on, so a call a little behind the last one (a simulated device's
        // substeps ask for the hand at t and at t + h) costs a step, not a scan from sample 0.
        if (cursor_ >= n - 1) cursor_ = n - 2;
        while (cursor_ > 0 && samples_[cursor_].t > t) --cursor_;
        while (cursor_ + 1 < n - 1 && samples_[cursor_ + 1].t <= t) ++cursor_;
        return true;
    }
    Interval interval(std::size_t k) const noexcept { return {samples_[k], samples_[k + 1], slopes_[k], k == 0}; }
    // The sample held outside the path (samples_ not empty): the first before it (and for a NaN
    // time), the last after it.
    const PathSample& held(double t) const noexcept { return t > samples_.front().t ? samples_.back() : samples_.front(); }

    std::vector<PathSample> samples_;
    // Each interval's slope (m/s), (x1 - x0) / (t1 - t0) as at() returns it, divided once here: a
    // simulated hand asks for the path every 0.1 ms substep, and the divisions were most of it.
    std::vector<Vec2> slopes_;
    mutable std::size_t cursor_ = 0;
};

HandPath read_hand_path_file(const std::string& path);

}  // namespace contactlab::drivers
