// hand_path.cpp — interpolation and the CSV reader for scripted hand paths.
#include "drivers/hand_path.hpp"

#include "haptics/finger_samples_csv.hpp"

namespace contactlab::drivers {

HandPath::HandPath(std::vector<PathSample> samples) : samples_(std::move(samples)) {
    if (samples_.empty()) throw HandPathError("hand path: no samples");
    for (std::size_t i = 1; i < samples_.size(); ++i)
        if (!(samples_[i].t > samples_[i - 1].t)) throw HandPathError("hand path: times must strictly increase");
    slopes_.reserve(samples_.size() - 1);
    for (std::size_t i = 1; i < samples_.size(); ++i) {
        const PathSample& a = samples_[i - 1];
        const PathSample& b = samples_[i];
        slopes_.push_back((b.x - a.x) / (b.t - a.t));
    }
}

void HandPath::append(const PathSample& s) {
    if (!samples_.empty() && !(s.t > samples_.back().t)) throw HandPathError("hand path: times must strictly increase");
    if (!samples_.empty()) slopes_.push_back((s.x - samples_.back().x) / (s.t - samples_.back().t));
    samples_.push_back(s);
}

bool HandPath::interval(double t, double& u) const noexcept {
    const std::size_t n = samples_.size();
    if (n == 0 || !(t > samples_.front().t) || t >= samples_.back().t) return false;
    // The interval is the last sample at or before t (and before the last sample): found from the
    // cursor, stepping back or on, so a call a little behind the last one (a simulated device's
    // substeps ask for the hand at t and at t + h) costs a step, not a scan from sample 0.
    if (cursor_ >= n - 1) cursor_ = n - 2;
    while (cursor_ > 0 && samples_[cursor_].t > t) --cursor_;
    while (cursor_ + 1 < n - 1 && samples_[cursor_ + 1].t <= t) ++cursor_;
    const PathSample& a = samples_[cursor_];
    const PathSample& b = samples_[cursor_ + 1];
    u = (t - a.t) / (b.t - a.t);
    return true;
}

PathPoint HandPath::at(double t) const noexcept {
    if (samples_.empty()) return {};
    double u = 0.0;
    if (!interval(t, u)) {
        const PathSample& s = held(t);
        return {s.x, Vec2{0.0}, s.phi};
    }
    const PathSample& a = samples_[cursor_];
    const PathSample& b = samples_[cursor_ + 1];
    return {a.x + (b.x - a.x) * u, slopes_[cursor_], a.phi + (b.phi - a.phi) * u};
}

double HandPath::phi_at(double t) const noexcept {
    if (samples_.empty()) return 0.0;
    double u = 0.0;
    if (!interval(t, u)) return held(t).phi;
    const PathSample& a = samples_[cursor_];
    const PathSample& b = samples_[cursor_ + 1];
    return a.phi + (b.phi - a.phi) * u;
}

// The file is the finger-path CSV `contactlab trace` reads (haptics/finger_samples_csv.hpp): one
// reader, one set of error messages.
HandPath read_hand_path_file(const std::string& path) {
    std::vector<PathSample> out;
    try {
        for (const FingerSample& s : read_finger_samples_file(path)) out.push_back({s.t, s.x, s.phi});
    } catch (const CsvError& e) {
        throw HandPathError(e.what());
    }
    if (out.empty()) throw HandPathError(path + ": no samples");
    return HandPath(std::move(out));
}

}  // namespace contactlab::drivers
