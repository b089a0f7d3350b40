// protocol.hpp — an experiment protocol file (scenes/experiments/*.json; schema in
// scenes/README.md, "Experiments"): the task, its conditions, stimuli, repetitions and order,
// warm-up, the answer set, the hand's motion, what makes a trial invalid, and the simulated
// participant's perception. Read strictly like a scene: an unknown key, a wrong type or a value
// out of range is an error naming the file, the JSON path and why.
//
// Room engine/experiments/protocol/: the protocol file and its reader (here), the psychometric functions it names,
// trial plans, grading, stimuli and surface profiles. Includes base/ only.
// The rooms and their arrows: docs/ARCHITECTURE.md, "The experiments' rooms".
#pragma once

#include "engine/experiments/protocol/psychometric.hpp"
#include "haptics/scene.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::experiments {

// The four seeds' tasks.
enum class Task {
    contour_following,    // seed 000: find the block's edge, tip round it, descend; timed
    bump_counting,        // seed 002: count the bumps (0..4) traced along a curved contour
    curvature,            // seed 003: which of three arc heights was felt
    surface_orientation,  // seed 004: the field's compliant axis at 45 or 135 deg: shape A or B
    // Park, Doxon, Provancher, Johnson & Tan 2011: which of two rounded edges (a reference and a
    // blunter comparison, in random order) felt sharper; two-alternative forced choice
    edge_sharpness,
};
const char* to_string(Task t);

struct Condition {
    std::string name;
    // The contact element displays the contact location; false holds it at the pad's centre
    // (seed 000's and 002's force-only condition).
    bool contact_location = true;
    // Seed 003: the arc's motion under the finger, "A" (the whole chord, -x to +x) or "B" (the
    // other way, +x to -x). Empty for the other tasks.
    std::string motion;
    // Seed 004: the field's eccentricity e and total stiffness k (N/m) in this condition.
    double eccentricity = 1.0, total_stiffness = 1000.0;
};

enum class HandModel { scripted, feel };
const char* to_string(HandModel h);
// "scripted" or "feel"; false for anything else.
bool parse_hand_model(const std::string& name, HandModel& out);
// Whether the task's simulated person has a hand that moves by feel: contour following (seed 000)
// and bump counting (seed 002). The others' strategies (a scripted press or slide) have none, so
// "feel" there would change nothing but the meta's record of which hand ran.
bool task_has_feel_hand(Task task);
// Why "feel" is refused for such a task, to follow "X is ": "a curvature protocol, whose simulated
// person has no hand that moves by feel (contour-following and bump-counting have one)". One text
// for the protocol loader, --hand and calibrate.
std::string no_feel_hand_reason(Task task);

// The people whose hands move by feel (`hand.model` "feel"): the population each simulated
// participant's hand is drawn from once (participants/person.hpp), each parameter's mean or
// median and spread, and the speeds and limits every such hand shares. A protocol's
// `participant.hand` object may change any of them, and `experiment calibrate --hand feel` fits
// them ("hand.NAME"); docs/experiments.md ("The hand that moves by feel") gives their sources.
struct HandPopulation {
    double delay_mean_s = 0.12, delay_sd_s = 0.02, delay_min_s = 0.08, delay_max_s = 0.20;  // normal, clipped
    double press_median_n = 0.7, press_log_sd = 0.2;                                        // log-normal
    double pace_log_sd = 0.3;                                                               // log-normal, median 1
    double trial_pace_log_sd = 0.0;  // log-normal, median 1: each trial's pace about the person's
    double force_noise_cv_mean = 0.1, force_noise_cv_sd = 0.02;                             // normal, at least 0.02
    double speed_noise_cv_mean = 0.15, speed_noise_cv_sd = 0.03;                            // normal, at least 0.03
    // Seed 002's free speed along the contour at the median pace (m/s): its people were told to
    // be quick.
    double slide_speed_mps = 0.08;
    // The guarded slide (feel_hand.hpp): pushing at this multiple of the target force, the hand
    // stops advancing (twice the target is where a person pressing at a few tenths of a newton
    // meets an obstacle rather than the surface: this model's choice).
    double hold_back = 2.0;
    // Seed 000 without contact location: the finger's pitch, which the person cannot see and,
    // without the display's contact location, does not feel, drifts as a random walk with the
    // hand's travel, of this many rad per sqrt(m) travelled (limb posture drifts with movement
    // made without feedback; docs/experiments.md). 0: none.
    double angle_drift_rad_sqrt_m = 0.4;
    // The force-direction threshold differs between people, not only from trial to trial: each
    // person's own mean is the participant model's force_angle_threshold_deg plus a normal draw
    // of this sd (deg). A person who notices the force's turn late has learnt to slide slower
    // along seed 000's top, where the pad left beyond their cue must last their stop time.
    double angle_threshold_sd_deg = 3.0;
};

// HandPopulation's numbers by name (a protocol's `participant.hand` keys, calibrate's
// "hand.NAME"), each with the range a protocol may give it.
struct HandField {
    const char* name;
    double HandPopulation::*member;
    double lo, hi;
    const char* unit;
};
const std::vector<HandField>& hand_population_fields();

// The simulated participant (sim_participant.hpp): one model of a person for every task. The
// thresholds of the cues it reads from what the device displayed and the Gaussian noise on each,
// in the units given, how it explores and how its attention lapses. The defaults are the person;
// a protocol's `participant` object may change any of them (the shipped ones do not).
// docs/experiments.md lists each parameter with its source or how it was fitted.
struct ParticipantModel {
    // A change of the force's direction it notices (deg): between the 14 deg at which a change of
    // direction of a point moving across the fingerpad is felt (Keyson & Houtsma 1995) and the
    // 25.6 deg between two force directions felt through a haptic device without vision
    // (Barbagli et al. 2006).
    double force_angle_threshold_deg = 15.0;
    double force_angle_noise_deg = 5.0;
    // A move of the contact element on the pad (mm): point localization on the fingertip is
    // 1-2 mm, between its gap detection (0.87 mm, Johnson & Phillips 1981) and its two-point
    // threshold (2-3 mm, Weinstein 1968).
    double location_threshold_mm = 1.5;
    double location_noise_mm = 0.5;
    // A bump felt through the arm (seed 002): the finger's height less its running mean over
    // 24 mm of travel must rise this far (mm) for the person to count a protrusion. Haptic
    // detection of a Gaussian bump on a flat surface needs 1 um at 0.15 mm wide to 8 mm at
    // 240 mm, a power law of exponent 1.3 (Louw, Kappers & Koenderink 2000): about 0.3 mm at
    // the 15-30 mm of seed 002's bumps. Counting one on a curved base needs more than detecting
    // it on a flat one; 0.7 mm, sd 0.2 mm, is this model's choice (docs/experiments.md).
    double path_threshold_mm = 0.7;
    double path_noise_mm = 0.2;
    // Seed 004: relative noise on felt stiffness, chosen so that seed 004's e = 0.40 gives about
    // its Table I (stiffness discrimination alone has a Weber fraction of about 0.2; the field's
    // two diagonals are felt one after the other, each through the hand's own compliance).
    double stiffness_noise = 0.5;
    // From noticing a cue to acting on it (s): the hand's corrective responses to touch come
    // about 100 ms after it (Jenmalm & Johansson 1997; 60-90 ms, Cole & Abbs 1988).
    double reaction_time_s = 0.1;
    // Trial-to-trial spread (sd, s) of the reaction time; each trial draws its own, never below
    // 30 ms. A coefficient of variation of 0.3, this model's choice (not from a source).
    double reaction_time_sd_s = 0.03;
    // Exploration speed where running past a feature fails the trial (seed 000's edge): the
    // person moves no faster than lets them stop in time, covering the pad left beyond where
    // their first cue reaches threshold (pad_length / 2 less the location threshold, or less
    // R sin(force angle threshold) without contact location) in `stop_time_s`, and never faster
    // than the protocol's hand speed. 0 keeps the protocol's hand speed. Fitted to seed 000's
    // failures and times (docs/experiments.md).
    double stop_time_s = 0.173;
    // Attention lapses while exploring (seed 000 and seed 002, where the stimulus passes once at
    // speed): lapses start at random (a Poisson process of `lapse_rate_hz` per second of the
    // trial) and last `lapse_duration_s`; a cue during one is not perceived (the last one felt
    // before it stays). Exploratory pauses of 67-330 ms are seen in haptic search (Grunwald et
    // al. 2014); the rate is fitted.
    double lapse_rate_hz = 0.5;
    double lapse_duration_s = 0.3;
    // Seed 003 on the wearable platform: relative noise (sd, a Weber fraction) on the range of
    // tilt the platform swept under the finger (wearable_trial.hpp). Relative, because people
    // judge a curvature by the difference of slope across the contact, and a range twice as large
    // is as discriminable from its neighbours as the smaller one is from its own.
    double tilt_range_noise = 0.15;
    // Edge sharpness: relative (Weber) noise on each felt peak rate of change, of the force's
    // direction and of the contact location, per edge felt.
    double edge_rate_noise = 0.1;
    // The people the hand that moves by feel belongs to (the scripted hand does not use them).
    HandPopulation hand;
};

// How the next trial's stimulus is chosen (procedure.hpp runs the adaptive ones).
enum class ProcedureType {
    constant,    // the method of constant stimuli: every stimulus `repetitions` times, shuffled
    staircase,   // transformed up-down (Levitt 1971), one staircase per condition, interleaved
    quest_plus,  // QUEST+ (Watson 2017): Bayesian, the stimulus minimising expected entropy
};
const char* to_string(ProcedureType t);

// Every field has a default, so {"type": "quest+"} alone is a procedure. Stimuli are in the
// protocol's stimulus units; `lo` and `hi` (the smallest and largest of the protocol's
// `stimuli`) bound every adaptive stimulus.
struct Procedure {
    ProcedureType type = ProcedureType::constant;
    double lo = 0.0, hi = 0.0;
    // Staircase: 1-up-N-down, N = `down` (1-up-2-down converges on p = 0.707, 1-up-3-down on
    // 0.794: p^N = 1/2). Starts at `start` (default hi, the easiest), moves by `step` (default
    // (hi - lo) / 8), the step halved at each reversal listed in `halve_at` (default 2 and 4:
    // large steps find the region, small ones measure it); stops after `reversals` reversals
    // or `max_trials` trials; the estimate is the mean stimulus at the last
    // `estimate_reversals` reversals (all of them when fewer).
    int down = 2;
    double start = NAN, step = NAN;
    std::vector<int> halve_at = {2, 4};
    int reversals = 16, estimate_reversals = 12, max_trials = 100;
    // QUEST+: the psychometric function and its grids (threshold over [lo, hi], `thresholds`
    // points; scale log-spaced over [scale_min, scale_max], `scales` points, default (hi - lo)
    // / 40 .. (hi - lo) / 2, or shape 1 .. 8 for the Weibull; lapse over [0, lapse_max],
    // `lapses` points); `levels` candidate stimuli over [lo, hi]; stops after `trials` trials or
    // when the threshold's 95 % credible interval is narrower than `stop_width` (0: never).
    PsyFunction function = PsyFunction::logistic;
    double guess = 0.5;
    int thresholds = 41, scales = 10, lapses = 4, levels = 41;
    double scale_min = NAN, scale_max = NAN, lapse_max = 0.06;
    int trials = 80;
    double stop_width = 0.0;
    // The probability correct the estimate aims at (staircase: 0.5^(1/down); QUEST+: the
    // threshold's, guess + (1 - guess) / 2 with no lapse).
    double target_p() const;
    std::string label() const;  // "staircase 1-up-2-down", "quest+", "constant"
};

struct Protocol {
    std::string origin;  // the file, for messages
    // The file's exact bytes and their SHA-256 (sha256.hpp): a results file's provenance names
    // the protocol that made it (RESULTS.csv.meta.json), and a resumed or pooled run is checked
    // against it.
    std::string text, sha256;
    std::string name;
    std::string seed_paper;  // "000", "002", "003", "004"
    Task task = Task::bump_counting;
    // The simulated device the trials run on (the results' `device` column): "sim-cld", the
    // contact location display rig (every task), or "sim-wearable", seed 003's fingertip platform
    // (the curvature task only: the finger held still, the arc moving under it; wearable_trial.hpp).
    std::string device = "sim-cld";
    std::vector<Condition> conditions;
    // Stimuli: the judged quantity's values (seed 000: d in m; 002: bump counts; 003: heights
    // in m; 004: field angles in deg).
    std::vector<double> stimuli;
    int repetitions = 1;          // presentations of each stimulus per condition
    int trials = 0;               // seed 002: trials per condition drawn at random (0: repetitions)
    int warmup = 0;               // first trials of each condition left out of the analysis
    bool repeat_invalid = true;   // an invalid trial is presented again at the end of its block
    std::vector<std::string> answers;  // the response set; empty for timed tasks
    // The hand: speed along the surface (m/s), press depth below it (m).
    double hand_speed = 0.05, hand_press = 0.003;
    // How the simulated person's hand moves (`hand.model`, or `experiment run --hand`):
    //   scripted  along a path made in advance from the contour (it knows the surface ahead)
    //   feel      closing its loop on what it feels, through a sensorimotor delay, with motor
    //             noise (participants/feel_hand.hpp); seed 000 and 002's tasks, the others keep
    //             their scripted slide or press
    HandModel hand_model = HandModel::scripted;
    // Seed 002's stimuli: bump heights (m) and the traced length (m); the base shape's vertical
    // span over that length (m). The default is the seed's text, 20 cm: its turns are then as
    // sharp as a small bump's top. The shipped 002-bump-counting.json sets 20 mm, a slowly-varying
    // base under the bumps (docs/experiments.md says why).
    double small_bump = 0.003, large_bump = 0.018, traced_length = 0.184, base_span = 0.20;
    double chord = 0.30;           // seed 003: the arc's chord (m)
    double finish_depth = 0.06;    // seed 000: the finish line below the block's top (m)
    double finger_radius = 0.026, pad_length = 0.020;  // m
    double stiffness = 1000.0;     // N/m (seeds 000, 002, 003)
    double max_force = 1.5;        // N
    // How the stimuli's curves (seed 002's quadratic Beziers) are rendered: exact by default; a
    // protocol may ask for flattened chords within a tolerance (m), a faster approximation whose
    // error and speed docs/experiments.md gives. Lines and arcs are exact either way.
    CurveDef curves;
    // Edge sharpness: the reference edge's radius (m) and the slope of the faces either side of
    // the edge (deg from horizontal); the stimulus is the comparison's radius less the
    // reference's, in mm.
    double reference_radius = 0.0025, edge_slope_deg = 30.0;
    Procedure procedure;
    ParticipantModel participant;
};

// The unit of the `stimulus` column for a task (the results' `stimulus_unit` column): "m"
// (000's d), "bumps" (002's count), "mm" (003's h and the edge's radius difference) and "deg"
// (004's alpha).
const char* stimulus_unit(Task t);

// Seed 004's template for a field angle alpha (deg): 0 (the protocol's first answer, template
// A) for 0 < alpha < 90, 1 (B) for 90 < alpha < 180. The axis is an axis, not a direction: at
// 0, 90 and 180 deg it is horizontal or vertical, tilted neither way, so neither template is
// right; protocols may not use those angles (parse_protocol refuses them).
int orientation_template(double alpha_deg);

// Two-alternative forced choice (edge sharpness): the interval, 1 or 2, that holds the
// comparison, drawn from the trial's seed alone (so a constant plan's order is untouched).
int comparison_interval(std::uint64_t trial_seed);

// The CSV text of a stimulus value: seed 003 in mm ("10"), others as written ("0.06", "2", "45").
std::string stimulus_label(const Protocol& p, double stimulus);

// A command's --hand NAME for protocol p: sets p.hand_model, or throws ExperimentError saying why
// not (not scripted or feel; feel for a task without such a hand, naming the protocol's file).
void apply_hand_option(Protocol& p, const std::string& name);

// Throws ExperimentError (results_table.hpp) naming the file, path and problem.
Protocol parse_protocol(const std::string& json_text, const std::string& origin);
Protocol load_protocol(const std::string& path);

}  // namespace contactlab::experiments
