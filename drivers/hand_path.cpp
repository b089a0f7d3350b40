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
