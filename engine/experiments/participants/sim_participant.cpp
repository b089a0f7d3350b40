// sim_participant.cpp — the simulated participant's perception and answers (sim_participant.hpp).
#include "engine/experiments/participants/sim_participant.hpp"

#include "engine/experiments/protocol/grading.hpp"
#include "engine/experiments/base/random_stream.hpp"
#include "engine/experiments/participants/cues.hpp"
#include "engine/experiments/participants/feel_tasks.hpp"
#include "engine/experiments/participants/servo_trial.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/participants/wearable_trial.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace contactlab::experiments {
namespace {

using drivers::TickRecord;
using namespace cues;

void common_measures(const TrialTrace& tr, TrialOutcome& o, double t_end = 1e300) {
    bool touched = false, prev = false;
    for (const TickRecord& r : tr.ticks) {
        if (r.t > t_end) break;
        o.peak_force = std::max(o.peak_force, std::hypot(r.force.x, r.force.y));
        if (touched && prev && !r.contact) ++o.contact_breaks;
        touched |= r.contact;
        prev = r.contact;
    }
    o.valid = !tr.faulted;
    // Over the whole trial, not up to t_end: a finger that first touches after the finish line
    // still touched the stimulus.
    o.touched = std::any_of(tr.ticks.begin(), tr.ticks.end(), [](const TickRecord& r) { return r.contact; });
    for (std::size_t i = 0; i < tr.ticks.size(); i += 10) o.shown.push_back(tr.ticks[i]);
}

// Share (0..1) of the ticks in [t0, t1] (s) in contact: the row's contact_fraction over the window
// its time_s measures. NaN when no tick lies there.
double contact_share(const TrialTrace& tr, double t0, double t1, long* in = nullptr, long* all = nullptr) {
    long n = 0, c = 0;
    for (const TickRecord& r : tr.ticks)
        if (r.t >= t0 && r.t <= t1) ++n, c += r.contact;
    if (in) *in += c;
    if (all) *all += n;
    return n > 0 ? static_cast<double>(c) / static_cast<double>(n) : NAN;
}

// Where rise-and-fall excursions of `s` beyond +-h complete (sample indices), counted either way
// round (a bump is + then - for one cue and may be - then + for another): the family with more.
// `felt(i)` says whether the person attended at sample i: an excursion completed during a lapse
// is not perceived.
template <class Felt>
std::vector<std::size_t> excursion_ends(const std::vector<double>& s, double h, Felt felt) {
    std::vector<std::size_t> pm, mp;
    int state = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double v = s[i];
        if (v > h && state != 1) {
            if (state == -1 && felt(i)) mp.push_back(i);
            state = 1;
        } else if (v < -h && state != -1) {
            if (state == 1 && felt(i)) pm.push_back(i);
            state = -1;
        }
    }
    return pm.size() >= mp.size() ? pm : mp;
}

// Protrusions of the finger's path: the spans [first, last] (sample indices) where `s` (its
// height less its running mean, m) stays above 0 and peaks above h, where the path turns over
// its peak (`turns_over(peak)`: a top, not the flank of a valley, which the running mean also
// lifts above 0) and the person attended there (`felt(peak)`).
template <class TurnsOver, class Felt>
std::vector<std::pair<std::size_t, std::size_t>> protrusions(const std::vector<double>& s, double h, TurnsOver turns_over,
                                                             Felt felt) {
    std::vector<std::pair<std::size_t, std::size_t>> out;
    for (std::size_t i = 0; i < s.size();) {
        if (!(s[i] > 0.0)) {
            ++i;
            continue;
        }
        std::size_t j = i, peak = i;
        for (; j < s.size() && s[j] > 0.0; ++j)
            if (s[j] > s[peak]) peak = j;
        if (s[peak] > h && turns_over(peak) && felt(peak)) out.emplace_back(i, j - 1);
        i = j;
    }
    return out;
}

// The contour as the arm reads it while the finger slides by feel: the person builds the
// contour's shape from where the finger touched it (the contour-following exploratory
// procedure yields exact shape, Lederman & Klatzky 1987), position by position along the
// travel, not tick by tick: where the finger went over a place more than once (it slipped back
// down a bump's face and climbed it again) the highest touch there is the surface (a finger
// pressed harder sinks further into it), and where it touched nothing (it lifted off a top and
// came down beyond) the surface is taken as straight between the touches either side. `at[k]`
// is the travel x (m) of sample k, `step` (m) the samples' spacing from `at[0]`; returns the
// height (m) of the finger's centre over each sample, or the arm's height where it never touched.
std::vector<double> felt_contour(const TrialTrace& tr, double t0, double t1, const std::vector<double>& at, double step,
                                 const std::vector<double>& arm) {
    const std::size_t n = at.size();
    std::vector<double> h(n, -1e300);
    if (n == 0) return h;
    for (const TickRecord& r : tr.ticks) {
        if (r.t < t0 || r.t > t1 || !r.contact) continue;
        const double k = std::floor((r.finger.x - at[0]) / step + 0.5);
        if (k < 0.0 || k >= static_cast<double>(n)) continue;
        double& v = h[static_cast<std::size_t>(k)];
        v = std::max(v, r.finger.y);
    }
    std::size_t first = 0;
    while (first < n && h[first] < -1e299) ++first;
    if (first == n) return arm;
    for (std::size_t k = 0; k < first; ++k) h[k] = h[first];
    for (std::size_t k = first + 1; k < n;) {
        if (h[k] > -1e299) {
            ++k;
            continue;
        }
        std::size_t b = k;
        while (b < n && h[b] < -1e299) ++b;
        for (std::size_t j = k; j < b; ++j)
            h[j] = b == n ? h[k - 1] : h[k - 1] + (h[b] - h[k - 1]) * static_cast<double>(j - k + 1) / static_cast<double>(b - k + 1);
        k = b;
    }
    return h;
}

// Curvature (1/m, negative where the path turns downward) of the path (x[i], y[i]) at sample i,
// from the samples `half` either side: the second difference over the slope's (1 + y'^2)^1.5.
double path_curvature(const std::vector<double>& x, const std::vector<double>& y, std::size_t i, std::size_t half) {
    const std::size_t a = i > half ? i - half : 0, b = std::min(x.size() - 1, i + half), m = (a + b) / 2;
    const double run = x[b] - x[a];  // m
    if (!(run > 0.0) || m == a || m == b) return 0.0;
    const double slope = (y[b] - y[a]) / run;
    const double second = ((y[b] - y[m]) / (x[b] - x[m]) - (y[m] - y[a]) / (x[m] - x[a])) / (0.5 * run);  // 1/m
    return second / std::pow(1.0 + slope * slope, 1.5);
}

// A band of `s`: its running mean over `narrow` samples each side less that over `wide`: what
// changes over a bump's width stays, the base shape's slow turn (and its slope) goes.
std::vector<double> band(const std::vector<double>& s, std::size_t narrow, std::size_t wide) {
    std::vector<double> prefix(s.size() + 1, 0.0), out(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) prefix[i + 1] = prefix[i] + s[i];
    auto mean = [&](std::size_t i, std::size_t half) {
        const std::size_t a = i > half ? i - half : 0, b = std::min(s.size(), i + half + 1);
        return (prefix[b] - prefix[a]) / static_cast<double>(b - a);
    };
    for (std::size_t i = 0; i < s.size(); ++i) out[i] = mean(i, narrow) - mean(i, wide);
    return out;
}

TrialOutcome contour_following(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng) {
    const ParticipantModel& m = p.participant;
    const double loc_threshold = noisy(m.location_threshold_mm, m.location_noise_mm, rng) * 1e-3;  // m
    const double angle_threshold = noisy(m.force_angle_threshold_deg, m.force_angle_noise_deg, rng);  // deg
    const double speed = exploration_speed(p, c);  // m/s along the top
    // This trial's reaction time (s); drawn only when it varies, as the lapses below.
    const double reaction = m.reaction_time_sd_s > 0.0 ? std::max(0.03, m.reaction_time_s + m.reaction_time_sd_s * normal01(rng))
                                                       : m.reaction_time_s;
    // Run 1: slide on past the edge; when is the edge noticed?
    const double far = 0.03;  // m past the edge: the pad is off the top by then
    const Stimulus first = make_stimulus(p, c, t, far, speed);
    const TrialTrace probe = run_servo_trial(first.scene, first.path, c.contact_location);
    const Lapses lapses = draw_lapses(m, 0.0, first.path.end(), rng);
    double overshoot = far;
    bool touched = false;
    for (const TickRecord& r : probe.ticks) {
        touched |= r.contact;
        if (!touched || r.finger.x < -t.stimulus) continue;  // before the start line
        if (lapses.at(r.t)) continue;                          // attending elsewhere
        const bool cue = (c.contact_location && std::abs(r.roller_l) >= loc_threshold) ||
                         (r.contact && std::abs(force_angle_deg(r)) >= angle_threshold) || !r.contact;
        if (cue) {
            overshoot = std::clamp(r.finger.x + speed * reaction, -0.005, far);
            break;
        }
    }
    // Run 2: the trial as performed, tipping round the edge `overshoot` past it.
    const Stimulus st = make_stimulus(p, c, t, overshoot, speed);
    const TrialTrace tr = run_servo_trial(st.scene, st.path, c.contact_location);
    TrialOutcome o;
    double t_start = -1.0, t_finish = -1.0;
    touched = false;
    for (const TickRecord& r : tr.ticks) {
        touched |= r.contact;
        if (t_start < 0.0 && touched && r.finger.x >= -t.stimulus) t_start = r.t;
        if (t_start >= 0.0 && r.finger.y <= -p.finish_depth) {
            t_finish = r.t;
            break;
        }
    }
    common_measures(tr, o, t_finish >= 0.0 ? t_finish : 1e300);
    o.time_s = t_start >= 0.0 && t_finish >= 0.0 ? t_finish - t_start : std::nan("");
    // From the start line to the finish line, or to the trial's end when the finish was missed.
    if (t_start >= 0.0) o.contact_fraction = contact_share(tr, t_start, t_finish >= 0.0 ? t_finish : 1e300);
    o.failed = o.contact_breaks > 0 || t_finish < 0.0;
    return o;
}

// Seed 000 with the hand that moves by feel (feel_tasks.hpp): timed and failed as the scripted
// trial is, from the start line to the finish line.
TrialOutcome contour_following_by_feel(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng) {
    const FeelTrial f = feel_contour_following(p, c, t, rng);
    TrialOutcome o;
    common_measures(f.trace, o, f.end >= 0.0 ? f.end : 1e300);
    o.time_s = f.start >= 0.0 && f.end >= 0.0 ? f.end - f.start : std::nan("");
    if (f.start >= 0.0) o.contact_fraction = contact_share(f.trace, f.start, f.end >= 0.0 ? f.end : 1e300);
    o.failed = o.contact_breaks > 0 || f.end < 0.0;
    return o;
}

// The ticks of [t0, t1] a count reads, in order: every tick for the scripted hand (constant
// speed), or for a hand whose speed varies, one per `step` m of the finger's travel in x (the
// tick where it first reaches each step; none while it goes back), so that the counting's
// windows, in samples, stay windows in mm.
std::vector<std::size_t> slide_ticks(const TrialTrace& tr, double t0, double t1, double step, bool by_travel) {
    std::vector<std::size_t> out;
    double next = -1e300;
    for (std::size_t i = 0; i < tr.ticks.size(); ++i) {
        const TickRecord& r = tr.ticks[i];
        if (r.t < t0 || r.t > t1) continue;
        if (!by_travel) {
            out.push_back(i);
            continue;
        }
        if (next < -1e299) next = r.finger.x;
        for (; r.finger.x >= next; next += step) out.push_back(i);
    }
    return out;
}

TrialOutcome bump_counting(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng) {
    const ParticipantModel& m = p.participant;
    const bool feel = p.hand_model == HandModel::feel;
    const Stimulus st = make_stimulus(p, c, t, 0.0, 0.0, feel ? PathUse::envelope : PathUse::script);
    FeelTrial f;
    if (feel) f = feel_slide(m.hand, c, t, st);
    else f.trace = run_servo_trial(st.scene, st.path, c.contact_location), f.start = st.slide_start, f.end = st.slide_end;
    const TrialTrace& tr = f.trace;
    std::vector<double> angle, location, height, travel, when;
    double last_angle = 0.0, last_loc = 0.0;
    const Lapses lapses = draw_lapses(m, f.start, f.end, rng);
    for (const std::size_t i : slide_ticks(tr, f.start, f.end, p.hand_speed / kTrialRate, feel)) {
        const TickRecord& r = tr.ticks[i];
        when.push_back(r.t);
        if (r.contact) {  // out of contact the finger feels nothing new: the last cue stays
            last_angle = force_angle_deg(r);
            last_loc = r.roller_l * 1e3;
        }
        angle.push_back(last_angle);
        location.push_back(last_loc);
        height.push_back(r.finger.y);  // the arm feels where the finger is, in contact or not
        travel.push_back(r.finger.x);
    }
    if (feel) height = felt_contour(tr, f.start, f.end, travel, p.hand_speed / kTrialRate, height);
    // Cues over a bump's width (15-30 mm): means over 4 mm less means over 16 mm of travel; the
    // finger's height less its mean over 24 mm (a bump lifts the finger over 30-50 mm of travel
    // once the 20 mm pad rolls over it).
    const double per_m = kTrialRate / p.hand_speed;  // samples per m of travel
    const auto narrow = static_cast<std::size_t>(0.002 * per_m), wide = static_cast<std::size_t>(0.008 * per_m),
               path_wide = static_cast<std::size_t>(0.012 * per_m);
    // A cue that completes during a lapse passes unfelt.
    const auto felt = [&](std::size_t i) { return !lapses.at(when[i]); };
    // Bumps as objects (docs/experiments.md, "The simulated person"): each rise of the finger's
    // path over a top is one bump, and so is every swing felt while the pad is still on it
    // (within a pad length of its span). Swings of the force's direction (and of the contact
    // element) felt elsewhere are bumps the arm did not notice; those within a pad length of each
    // other are the same one (the element swings both ways over one bump, the force turns at its
    // foot and at its top). A top: the path turns over it more sharply than a 50 mm radius, over
    // +-8 mm of travel (a bump's top, rounded by the 20 mm pad, turns the finger at 24-35 mm).
    const auto top_half = static_cast<std::size_t>(0.008 * per_m);
    const auto turns_over = [&](std::size_t i) { return path_curvature(travel, height, i, top_half) < -1.0 / 0.05; };
    const auto bumps = protrusions(band(height, narrow, path_wide), noisy(m.path_threshold_mm, m.path_noise_mm, rng) * 1e-3,
                                   turns_over, felt);
    // The feel hand's person has their own force-direction threshold (as in seed 000); the
    // scripted person's is the model's.
    const double angle_mean =
        feel ? std::max(1.0, m.force_angle_threshold_deg + f.person.angle_threshold_offset_deg) : m.force_angle_threshold_deg;  // deg
    std::vector<std::size_t> swings = excursion_ends(band(angle, narrow, wide), noisy(angle_mean, m.force_angle_noise_deg, rng), felt);
    if (c.contact_location) {
        const auto element =
            excursion_ends(band(location, narrow, wide), noisy(m.location_threshold_mm, m.location_noise_mm, rng), felt);
        swings.insert(swings.end(), element.begin(), element.end());
    }
    std::vector<double> elsewhere;  // m of travel
    for (const std::size_t i : swings) {
        const double x = travel[i];
        const bool on_a_bump = std::any_of(bumps.begin(), bumps.end(), [&](const auto& b) {
            return x >= travel[b.first] - p.pad_length && x <= travel[b.second] + p.pad_length;
        });
        if (!on_a_bump) elsewhere.push_back(x);
    }
    std::sort(elsewhere.begin(), elsewhere.end());
    int count = static_cast<int>(bumps.size());
    for (std::size_t k = 0; k < elsewhere.size(); ++k)
        if (k == 0 || elsewhere[k] - elsewhere[k - 1] > p.pad_length) ++count;
    TrialOutcome o;
    common_measures(tr, o);
    o.small_bumps = st.small_bumps;
    o.large_bumps = st.large_bumps;
    // The answers are the counts 0..N (parse_protocol checks it): a larger count is answered N.
    o.response = std::to_string(std::clamp(count, 0, static_cast<int>(p.answers.size()) - 1));
    o.time_s = f.end - f.start;
    o.contact_fraction = contact_share(tr, f.start, f.end);
    return o;
}

TrialOutcome curvature(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng) {
    const ParticipantModel& m = p.participant;
    const Stimulus st = make_stimulus(p, c, t);
    const TrialTrace tr = run_servo_trial(st.scene, st.path, c.contact_location);
    double lo = 1e9, hi = -1e9;
    for (const TickRecord& r : tr.ticks)
        if (r.t >= st.slide_start && r.t <= st.slide_end && r.contact) {
            lo = std::min(lo, force_angle_deg(r));
            hi = std::max(hi, force_angle_deg(r));
        }
    const double felt = (hi > lo ? hi - lo : 0.0) + m.force_angle_noise_deg * normal01(rng);
    double best = 1e300, answer = p.stimuli.front();
    for (double h : p.stimuli)
        if (const double d = std::abs(felt - arc_slope_range_deg(p.chord, h)); d < best) {
            best = d;
            answer = h;
        }
    TrialOutcome o;
    common_measures(tr, o);
    o.response = stimulus_label(p, answer);
    o.time_s = st.slide_end - st.slide_start;
    o.contact_fraction = contact_share(tr, st.slide_start, st.slide_end);
    return o;
}

// Force magnitude (N) and finger position at the last tick at or before time `at`.
const TickRecord* at_time(const TrialTrace& tr, double at) {
    const TickRecord* best = nullptr;
    for (const TickRecord& r : tr.ticks)
        if (r.t <= at) best = &r;
    return best;
}

TrialOutcome surface_orientation(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng) {
    const ParticipantModel& m = p.participant;
    const Stimulus st = make_stimulus(p, c, t);
    const TrialTrace tr = run_servo_trial(st.scene, st.path, c.contact_location);
    // Stiffness felt along a diagonal: force growth over the finger's displacement (N/m).
    auto felt = [&](double from, double to) {
        const TickRecord* a = at_time(tr, from);
        const TickRecord* b = at_time(tr, to);
        if (!a || !b) return 0.0;
        const double dx = glm::length(b->finger - a->finger);
        const double df = std::hypot(b->force.x, b->force.y) - std::hypot(a->force.x, a->force.y);
        return (dx > 0.0 ? df / dx : 0.0) * (1.0 + m.stiffness_noise * normal01(rng));
    };
    const double down_left = felt(st.probe[0], st.probe[1]), down_right = felt(st.probe[2], st.probe[3]);
    TrialOutcome o;
    common_measures(tr, o);
    // a1 at 45 deg runs up-right/down-left: pressing down-left is the soft way (template A).
    o.response = down_left < down_right ? p.answers.front() : p.answers.back();
    o.time_s = st.path.end() - st.path.start();
    o.contact_fraction = contact_share(tr, st.path.start(), st.path.end());
    return o;
}

// Peak rate of change per mm of travel of a cue sampled every tick at constant hand speed,
// after a running mean over +-2 mm (the skin and the hand do not resolve finer).
double peak_rate_per_mm(const std::vector<double>& s, double samples_per_mm) {
    if (s.size() < 3) return 0.0;
    const std::size_t half = static_cast<std::size_t>(2.0 * samples_per_mm);
    // band(s, half, 0) is the running mean over +-half less the sample itself: add it back.
    std::vector<double> m = band(s, half, 0);
    for (std::size_t i = 0; i < s.size(); ++i) m[i] += s[i];
    double peak = 0.0;
    const std::size_t lag = std::max<std::size_t>(1, static_cast<std::size_t>(samples_per_mm));
    for (std::size_t i = lag; i < m.size(); ++i) peak = std::max(peak, std::abs(m[i] - m[i - lag]));
    return peak;  // per lag samples = per mm
}

struct EdgeFelt {
    double angle_rate = 0.0, location_rate = 0.0;  // deg/mm, mm/mm
    TrialTrace trace;
    Stimulus st;
};

EdgeFelt feel_edge(const Protocol& p, const Condition& c, double radius) {
    EdgeFelt f;
    f.st = make_edge_stimulus(p, radius);
    f.trace = run_servo_trial(f.st.scene, f.st.path, c.contact_location);
    std::vector<double> angle, location;
    double last_angle = 0.0, last_loc = 0.0;
    for (const TickRecord& r : f.trace.ticks) {
        if (r.t < f.st.slide_start || r.t > f.st.slide_end) continue;
        if (r.contact) last_angle = force_angle_deg(r), last_loc = r.roller_l * 1e3;
        angle.push_back(last_angle);
        location.push_back(last_loc);
    }
    const double per_mm = kTrialRate / (p.hand_speed * 1e3);
    f.angle_rate = peak_rate_per_mm(angle, per_mm);
    f.location_rate = peak_rate_per_mm(location, per_mm);
    return f;
}

TrialOutcome edge_sharpness(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng) {
    const double noise = p.participant.edge_rate_noise;
    const EdgeFelt first = feel_edge(p, c, edge_radius(p, t, 1)), second = feel_edge(p, c, edge_radius(p, t, 2));
    // A felt rate: the displayed one with relative noise, kept positive.
    auto felt = [&](double rate) { return std::max(1e-9, rate * std::max(0.05, 1.0 + noise * normal01(rng))); };
    double d = std::log(felt(first.angle_rate) / felt(second.angle_rate));
    if (c.contact_location) d = 0.5 * (d + std::log(felt(first.location_rate) / felt(second.location_rate)));
    TrialOutcome o;
    // Both intervals count: a fault or no contact in either spoils the comparison.
    TrialTrace both = first.trace;
    const double offset = first.st.path.end();
    for (drivers::TickRecord r : second.trace.ticks) {
        r.t += offset;
        both.ticks.push_back(r);
    }
    both.faulted = first.trace.faulted || second.trace.faulted;
    common_measures(both, o);
    o.touched = std::any_of(first.trace.ticks.begin(), first.trace.ticks.end(), [](const TickRecord& r) { return r.contact; }) &&
                std::any_of(second.trace.ticks.begin(), second.trace.ticks.end(), [](const TickRecord& r) { return r.contact; });
    o.response = d > 0.0 ? p.answers[0] : p.answers[1];
    o.time_s = (first.st.slide_end - first.st.slide_start) + (second.st.slide_end - second.st.slide_start);
    long in = 0, all = 0;  // ticks in contact, ticks, over both slides
    contact_share(first.trace, first.st.slide_start, first.st.slide_end, &in, &all);
    contact_share(second.trace, second.st.slide_start, second.st.slide_end, &in, &all);
    if (all > 0) o.contact_fraction = static_cast<double>(in) / static_cast<double>(all);
    return o;
}

}  // namespace

TrialOutcome perform_sim_trial(const Protocol& p, const PlannedTrial& t) {
    const Condition& c = p.conditions.at(static_cast<std::size_t>(t.condition));
    std::uint64_t rng = mix64(t.seed ^ 0x5EEDull);
    TrialOutcome o;
    switch (p.task) {
        case Task::contour_following:
            o = p.hand_model == HandModel::feel ? contour_following_by_feel(p, c, t, rng) : contour_following(p, c, t, rng);
            break;
        case Task::bump_counting: o = bump_counting(p, c, t, rng); break;
        case Task::curvature:
            o = p.device == "sim-wearable" ? wearable_curvature_trial(p, c, t, rng) : curvature(p, c, t, rng);
            break;
        case Task::surface_orientation: o = surface_orientation(p, c, t, rng); break;
        case Task::edge_sharpness: o = edge_sharpness(p, c, t, rng); break;
    }
    o.correct = graded_correct(p, t, o.response);
    return o;
}

}  // namespace contactlab::experiments
