// feel_tasks.cpp — the feel hand's strategies per task (feel_tasks.hpp).
#include "engine/experiments/participants/feel_tasks.hpp"

#include "engine/experiments/participants/cues.hpp"
#include "engine/experiments/participants/feel_hand.hpp"
#include "engine/experiments/participants/person.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab::experiments {
namespace {

using drivers::PathSample;
using drivers::TickRecord;
using namespace cues;

constexpr double kReach = 0.03;  // m/s: reaching down for a surface not yet touched
constexpr double kSettle = 0.3;  // s of contact felt before sliding off (the scripted hand settles 0.2-0.3 s)
// Tipping round an edge: the finger turned this far ahead of the felt normal (rad; the felt
// normal lags the real one by the delay times the rate of turn, 0.12 s x 30 mm/s / 26 mm =
// 0.14 rad at the corner's speed), and the motion turned this far down from the felt tangent
// (rad): the person stops going on and goes down round the edge, pressed onto it.
constexpr double kTipLead = 0.15, kTipTurn = 0.5;
// The hand in series with a rendered surface (N/m), as the person has learnt it in practice.
constexpr double kSeriesStiffness = 240.0;

// How far past the edge (m, the finger's centre) the person can slide before the pad leaves
// the top: half the pad (as the scripted person's speed takes it, 10 mm), or sooner where they press
// lightly: the hand means the finger to be F* / k below where it is, so it leaves the corner's
// circle of radius R where the intended point does, sqrt(2 R F* / k) past the edge.
double reach_past_edge(const Protocol& p, const Person& person) {
    return std::min(0.5 * p.pad_length, std::sqrt(2.0 * p.finger_radius * person.press_force_n / kSeriesStiffness));
}

// The time the pad left beyond the first cue must last for this person (s): their reaction, and
// the tip round the edge getting under way, which takes kTipDelays of their feedback delays (the
// hand learns that the finger turned only a delay after it did). It replaces the scripted
// person's fitted stop_time_s: the feel hand has to do the tipping the scripted path did at once.
constexpr double kTipDelays = 1.0;
double stop_time(const ParticipantModel& m, const Person& person) { return m.reaction_time_s + kTipDelays * person.delay_s; }

// The speed along the top (m/s): as the scripted person's (cues.hpp), the pad they can still use
// beyond their first cue lasting stop_time(), that pad being what reach_past_edge leaves them;
// a faster-paced person leaving it less time, at most the protocol's hand speed (their free
// speed's cap). stop_time_s 0 keeps the hand speed, as for the scripted person.
double top_speed(const Protocol& p, const Condition& c, const Person& person, double angle_threshold_deg) {
    const ParticipantModel& m = p.participant;
    if (m.stop_time_s <= 0.0) return p.hand_speed;
    double cue = p.finger_radius * std::sin(std::min(90.0, angle_threshold_deg) / kDeg);  // m past the edge
    if (c.contact_location) cue = std::min(cue, m.location_threshold_mm * 1e-3);
    const double left = std::max(0.0, reach_past_edge(p, person) - cue);  // m
    return std::clamp(left * person.pace / stop_time(m, person), 0.002, p.hand_speed);
}

// Readiness for the edge grows with its hazard (the variable-foreperiod effect: people respond
// faster, and miss less, the likelier the signal is to come now; Niemi & Naatanen 1981,
// Psychological Bulletin 89(1)). The person has learnt that the edge comes d_min to d_max past the
// start line, each as likely (the protocol's stimuli); the edge's hazard there is 1 / (d_max - s)
// at s travelled. Their lapse rate scales inversely with it, equal to lapse_rate_hz where the
// hazard is its middle value's, 1 / (d_max - (d_min + d_max) / 2), as the square of their ratio
// (this model's choice, fitted by eye to seed 000's failures with contact location falling from
// 26 % at 4 cm to 2-5 % at 8-10 cm), and held at its d_min value before d_min (the edge cannot come
// yet, and attention is at its loosest).
double lapse_scale(const Protocol& p, double travelled) {
    const auto [lo, hi] = std::minmax_element(p.stimuli.begin(), p.stimuli.end());
    if (!(*hi > *lo)) return 1.0;
    const double mid = 0.5 * (*lo + *hi), s = std::clamp(travelled, *lo, *hi);
    const double ratio = (*hi - s) / (*hi - mid);  // the middle hazard over the hazard here
    return ratio * ratio;
}
constexpr double kCornerShare = 1.0;  // round the corner at this share of the free speed
// Seed 000: the free speed ends this long (s, at free speed) before the shortest block: two of
// the hand's 0.15 s speed time constants, so it is down to the top speed where the edge can come.
constexpr double kEarlyMargin = 0.3;

}  // namespace

FeelTrial feel_contour_following(const Protocol& p, const Condition& c, const PlannedTrial& t, std::uint64_t& rng) {
    const ParticipantModel& m = p.participant;
    Person person = draw_person(t.person, m.hand);
    person.pace = trial_pace(person, m.hand, t.seed);
    // The scripted person's draws, in its order: the same person notices the same way.
    const double loc_threshold = noisy(m.location_threshold_mm, m.location_noise_mm, rng) * 1e-3;    // m
    // The person's own force-direction threshold (deg): the model's, moved by where this person
    // lies in the population; the trial's threshold varies about it.
    const double person_angle = std::max(1.0, m.force_angle_threshold_deg + person.angle_threshold_offset_deg);
    const double angle_threshold = noisy(person_angle, m.force_angle_noise_deg, rng);  // deg
    const double reaction = m.reaction_time_sd_s > 0.0 ? std::max(0.03, m.reaction_time_s + m.reaction_time_sd_s * normal01(rng))
                                                       : m.reaction_time_s;  // s
    const double v_top = top_speed(p, c, person, person_angle);  // m/s along the top
    const double v_free = p.hand_speed * person.pace;             // m/s round the corner and down
    const double d = t.stimulus;                                  // m
    const double d_min = *std::min_element(p.stimuli.begin(), p.stimuli.end());  // m, the shortest block
    // Long enough for the slowest person to reach the finish; a trial that does not has failed.
    const double max_s = 2.0 + 2.0 * (d + 0.02) / v_top + 2.0 * (0.05 + p.finish_depth) / (kCornerShare * v_free);
    // Candidate lapses at the largest rate the hazard allows, each kept with the rate's share at
    // the distance travelled when it starts (thinning a Poisson process): at most four times
    // lapse_rate_hz, at the shortest block.
    ParticipantModel loosest = m;
    loosest.lapse_rate_hz = m.lapse_rate_hz * lapse_scale(p, -1.0);
    Lapses lapses = draw_lapses(loosest, 0.0, max_s, rng);
    std::vector<double> keep(lapses.starts.size());
    for (double& u : keep) u = uniform01(rng);
    std::size_t next_lapse = 0;  // the next candidate lapse to decide on
    Lapses kept;
    kept.duration = lapses.duration;
    const Stimulus st = make_stimulus(p, c, t, 0.006, v_top);  // the scene, and the rig's envelope
    const PathSample start{0.0, Vec2{-d - 0.01, p.finger_radius + 0.01}, 0.0};
    FeelHand hand(person, start, 1.0 / kTrialRate, t.seed);
    hand.set_approach(kReach);
    hand.hold_angle(0.0);
    enum class Phase { reach, slide, noticed, round, descend } phase = Phase::reach;
    double felt_since = -1.0, act_at = 0.0;  // s
    bool touched = false;
    FeelTrial out;
    out.person = person;
    const Steer steer = [&](const TickRecord& r, PathSample& next) {
        touched |= r.contact;
        if (out.start < 0.0 && touched && r.finger.x >= -d) out.start = r.t;
        // Lapses starting now: kept by the hazard at the distance the arm says was travelled
        // past the start line.
        for (; next_lapse < lapses.starts.size() && lapses.starts[next_lapse] <= r.t; ++next_lapse)
            if (keep[next_lapse] * lapse_scale(p, -1.0) < lapse_scale(p, r.finger.x + d)) kept.starts.push_back(lapses.starts[next_lapse]);
        if (out.start >= 0.0 && r.finger.y <= -p.finish_depth) {
            out.end = r.t;
            return false;
        }
        switch (phase) {
            case Phase::reach:
                if (hand.felt_contact() && felt_since < 0.0) felt_since = r.t;
                if (felt_since >= 0.0 && r.t - felt_since >= kSettle) {
                    hand.set_speed(v_top);
                    // Without contact location the person does not feel where on the pad the
                    // contact is, and their finger's pitch drifts unnoticed from here on.
                    hand.set_drifting(!c.contact_location);
                    phase = Phase::slide;
                }
                break;
            case Phase::slide: {
                // Where the edge cannot come yet (less than the shortest block past the start line,
                // as the arm tells the distance), nothing needs stopping for: the person goes at
                // their free speed, slowing to v_top in time to be at it there (two of the
                // speed's time constants ahead, kEarlyMargin). The hazard that shapes their
                // lapses (lapse_scale) shapes their speed too (Niemi & Naatanen 1981).
                hand.set_speed(r.finger.x + d < d_min - kEarlyMargin * v_free ? std::max(v_top, v_free) : v_top);
                // The edge noticed (the scripted person's cues) past the start line, outside lapses.
                if (r.finger.x < -d || kept.at(r.t)) break;
                const bool cue = (c.contact_location && std::abs(r.roller_l) >= loc_threshold) ||
                                 (r.contact && std::abs(force_angle_deg(r)) >= angle_threshold) || !r.contact;
                if (cue) {
                    act_at = r.t + reaction;
                    phase = Phase::noticed;
                }
                break;
            }
            case Phase::noticed:
                if (r.t >= act_at) {  // tip round the edge
                    hand.set_speed(kCornerShare * v_free);
                    hand.set_turn(kTipTurn);
                    hand.set_guarded(false);  // pressing round the corner on purpose
                    hand.follow_normal(kTipLead);
                    phase = Phase::round;
                }
                break;
            case Phase::round:
                if (hand.felt_normal().x > 0.9) {  // beside the far face: straight down it
                    hand.set_turn(0.0);
                    hand.set_speed(v_free);
                    phase = Phase::descend;
                }
                break;
            case Phase::descend: break;
        }
        next = hand.step(r);
        return true;
    };
    out.trace = run_steered_trial(st.scene, st.path, start, c.contact_location, steer, max_s);
    return out;
}

FeelTrial feel_slide(const HandPopulation& people, const Condition& c, const PlannedTrial& t, const Stimulus& st) {
    FeelTrial out;
    Person& person = out.person;
    person = draw_person(t.person, people);
    person.pace = trial_pace(person, people, t.seed);
    // Seed 002's people were told to be quick: 18.4 cm in 4.1-4.5 s, 41-45 mm/s on average, the
    // bumps taken slower. The free speed at the median pace (HandPopulation::slide_speed_mps,
    // 80 mm/s) is fitted to that time per trial (docs/experiments.md gives the fit).
    const double v_free = person.slide_speed_mps * person.pace;  // m/s
    const double x0 = st.path.samples().front().x.x;
    // The slide ends where the scripted one does: its path's x at slide_end.
    const double x1 = st.path.at(st.slide_end).x.x;
    const double max_s = 2.0 + 3.0 * std::abs(x1 - x0) / v_free;
    const PathSample start = st.path.samples().front();
    FeelHand hand(person, start, 1.0 / kTrialRate, t.seed);
    hand.set_approach(kReach);
    hand.follow_normal(0.0);
    double felt_since = -1.0;   // s
    // rad; rad/s: the felt normal's rate of turn, unsigned and signed (counter-clockwise
    // positive), low-passed over 0.1 s.
    double last_angle = 0.0, turn_rate = 0.0, turn_signed = 0.0;
    bool sliding = false;
    // The felt turn's low-pass over 0.1 s: its coefficient a tick, the same every tick.
    const double low = 1.0 - std::exp(-1.0 / (0.1 * kTrialRate));
    const Steer steer = [&](const TickRecord& r, PathSample& next) {
        if (!sliding) {
            if (hand.felt_contact() && felt_since < 0.0) felt_since = r.t;
            if (felt_since >= 0.0 && r.t - felt_since >= kSettle) {
                sliding = true;
                out.start = r.t;
                last_angle = std::atan2(hand.felt_normal().y, hand.felt_normal().x);
            }
        } else {
            if (r.finger.x >= x1) {
                out.end = r.t;
                return false;
            }
            // Speed from the felt contour's curvature: the felt normal's rate of turn over the
            // speed; at most the free speed, slower as curvature^(-1/3) beyond 1 / 20 mm (a
            // bump's top under the 20 mm pad; the base's turns, 1 / 50 mm and gentler, and the
            // felt normal's own noise leave the free speed alone).
            const double a = std::atan2(hand.felt_normal().y, hand.felt_normal().x);
            double da = a - last_angle;
            if (da > kPi) da -= 2.0 * kPi;
            if (da < -kPi) da += 2.0 * kPi;
            last_angle = a;
            turn_rate += (std::abs(da) * kTrialRate - turn_rate) * low;
            turn_signed += (da * kTrialRate - turn_signed) * low;
            // What the hand feels is a delay old: the contour has turned on by the felt rate of
            // turn times the delay since, and the hand moves along the felt tangent turned that
            // much further (a forward model predicting the felt normal over the feedback delay,
            // Miall & Wolpert 1996): into the surface over a bump's top (the normal turning
            // clockwise, da < 0), away from it where the contour rises ahead; never by more than
            // the 0.5 rad of seed 000's deliberate tip.
            hand.set_turn(std::clamp(-turn_signed * person.delay_s, -kTipTurn, kTipTurn));
            const double curvature = turn_rate / std::max(0.005, hand.speed());  // 1/m
            hand.set_speed(curvature > 50.0 ? v_free * std::cbrt(50.0 / curvature) : v_free);
        }
        next = hand.step(r);
        return true;
    };
    out.trace = run_steered_trial(st.scene, st.path, start, c.contact_location, steer, max_s);
    if (out.start >= 0.0 && out.end < 0.0 && !out.trace.ticks.empty()) out.end = out.trace.ticks.back().t;
    return out;
}

}  // namespace contactlab::experiments
