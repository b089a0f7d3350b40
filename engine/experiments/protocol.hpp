// protocol.hpp — an experiment protocol file (scenes/experiments/*.json; schema in
// scenes/README.md, "Experiments"): the task, its conditions, stimuli, repetitions and order,
// warm-up, the answer set, the hand's motion, what makes a trial invalid, and the simulated
// participant's perception. Read strictly like a scene: an unknown key, a wrong type or a value
// out of range is an error naming the file, the JSON path and why.
#pragma once

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
};
const char* to_string(Task t);

struct Condition {
    std::string name;
    // The contact element displays the contact location; false holds it at the pad's centre
    // (seed 000's and 002's force-only condition).
    bool contact_location = true;
    // Seed 003: the arc's motion under the finger, "A" (the whole chord) or "B" (from its top
    // to its end). Empty for the other tasks.
    std::string motion;
    // Seed 004: the field's eccentricity e and total stiffness k (N/m) in this condition.
    double eccentricity = 1.0, total_stiffness = 1000.0;
};

// Perception of the simulated participant (sim_participant.hpp): thresholds of the cues it reads
// from what the device displayed, and the Gaussian noise on each, in the units given.
struct ParticipantModel {
    double force_angle_threshold_deg = 6.0;  // a change of the force's direction it notices
    double force_angle_noise_deg = 3.0;
    double location_threshold_mm = 2.0;      // a move of the contact element on the pad
    double location_noise_mm = 1.0;
    double stiffness_noise = 0.15;           // seed 004: relative noise on felt stiffness
    double reaction_time_s = 0.25;           // from noticing a cue to acting on it
    // Seed 003 on the wearable platform: relative noise (sd, a Weber fraction) on the range of
    // tilt the platform swept under the finger (wearable_trial.hpp). Relative, because people
    // judge a curvature by the difference of slope across the contact, and a range twice as large
    // is as discriminable from its neighbours as the smaller one is from its own.
    double tilt_range_noise = 0.15;
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
    // Seed 002's stimuli: bump heights (m) and the traced length (m).
    double small_bump = 0.003, large_bump = 0.018, traced_length = 0.184;
    double chord = 0.30;           // seed 003: the arc's chord (m)
    double finish_depth = 0.06;    // seed 000: the finish line below the block's top (m)
    double finger_radius = 0.026, pad_length = 0.020;  // m
    double stiffness = 1000.0;     // N/m (seeds 000, 002, 003)
    double max_force = 1.5;        // N
    ParticipantModel participant;
};

// The unit of the `stimulus` column for a task (the results' `stimulus_unit` column): "m"
// (000's d), "bumps" (002's count), "mm" (003's h) and "deg" (004's alpha).
const char* stimulus_unit(Task t);

// Seed 004's template for a field angle alpha (deg): 0 (the protocol's first answer, template
// A) for 0 < alpha < 90, 1 (B) for 90 < alpha < 180. The axis is an axis, not a direction: at
// 0, 90 and 180 deg it is horizontal or vertical, tilted neither way, so neither template is
// right; protocols may not use those angles (parse_protocol refuses them).
int orientation_template(double alpha_deg);

// The CSV text of a stimulus value: seed 003 in mm ("10"), others as written ("0.06", "2", "45").
std::string stimulus_label(const Protocol& p, double stimulus);

// Throws ExperimentError (results_table.hpp) naming the file, path and problem.
Protocol parse_protocol(const std::string& json_text, const std::string& origin);
Protocol load_protocol(const std::string& path);

}  // namespace contactlab::experiments
