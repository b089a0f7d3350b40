// cues.hpp — how the simulated person notices things in what the device displayed: the force's
// direction, thresholds with perceptual noise, attention lapses, and the speed along seed 000's
// top that lets them stop in time. Shared by the scripted hand's tasks (sim_participant.cpp)
// and the feel hand's (feel_tasks.cpp), so both hands notice alike.
#pragma once

#include "drivers/tick_record.hpp"
#include "engine/experiments/base/random_stream.hpp"
#include "engine/experiments/protocol/protocol.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace contactlab::experiments::cues {

using drivers::TickRecord;

constexpr double kDeg = 180.0 / kPi;

// The force's direction from the vertical (deg), positive when it pushes back (-x) as on a
// rising slope under a finger moving +x.
inline double force_angle_deg(const TickRecord& r) { return std::atan2(-r.force.x, r.force.y) * kDeg; }

// A threshold with perceptual noise, never below a tenth of itself.
inline double noisy(double threshold, double noise, std::uint64_t& rng) {
    return std::max(0.1 * threshold, threshold + noise * normal01(rng));
}

// Attention lapses over [t0, t1] s (ParticipantModel::lapse_rate_hz): start times of a Poisson
// process, each lapse `lapse_duration_s` long. Draws nothing when the rate is 0, so a model
// without lapses keeps its random stream as before.
struct Lapses {
    std::vector<double> starts;  // s
    double duration = 0.0;       // s
    bool at(double t) const {
        for (double s : starts)
            if (t >= s && t < s + duration) return true;
        return false;
    }
};

inline Lapses draw_lapses(const ParticipantModel& m, double t0, double t1, std::uint64_t& rng) {
    Lapses l;
    l.duration = m.lapse_duration_s;
    if (m.lapse_rate_hz <= 0.0 || m.lapse_duration_s <= 0.0) return l;
    for (double t = t0 - m.lapse_duration_s;;) {
        t += -std::log(1.0 - uniform01(rng)) / m.lapse_rate_hz;  // exponential gaps
        if (t >= t1) break;
        l.starts.push_back(t);
    }
    return l;
}

// The speed (m/s) along seed 000's top: what lets the person stop within the pad after their
// first cue (ParticipantModel::stop_time_s), from their usual thresholds, not this trial's draw.
inline double exploration_speed(const Protocol& p, const Condition& c) {
    const ParticipantModel& m = p.participant;
    if (m.stop_time_s <= 0.0) return p.hand_speed;
    double cue = p.finger_radius * std::sin(std::min(90.0, m.force_angle_threshold_deg) / kDeg);  // m past the edge
    if (c.contact_location) cue = std::min(cue, m.location_threshold_mm * 1e-3);
    const double left = std::max(0.0, 0.5 * p.pad_length - cue);  // m of pad beyond the cue
    return std::clamp(left / m.stop_time_s, 0.002, p.hand_speed);  // never slower than 2 mm/s
}

}  // namespace contactlab::experiments::cues
