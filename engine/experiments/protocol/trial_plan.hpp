// trial_plan.hpp — the order of an experiment's trials for one participant, from the protocol
// and a seed: reproducible (the same seed, participant and protocol give the same order on any
// machine: splitmix64 (base/random_stream.hpp) and a Fisher-Yates shuffle written here, not the
// standard library's implementation-defined distributions).
//
// One block per condition. With two conditions they alternate between participants (the first
// participant gets the protocol's order, the second the reverse, ...), as seeds 000 and 002
// balanced theirs; with more, each participant gets them in a shuffled order. In a block each
// stimulus is presented `repetitions` times in shuffled order, or (seed 002) `trials` trials each
// draw a stimulus with equal probability. The first `warmup` trials of a block are warm-up.
#pragma once

#include "engine/experiments/protocol/protocol.hpp"

#include <cstdint>
#include <vector>

namespace contactlab::experiments {

struct PlannedTrial {
    int condition = 0;        // index into Protocol::conditions
    int trial = 0;            // 1-based within the block
    double stimulus = 0.0;    // the judged quantity (protocol units)
    bool warmup = false;
    std::uint64_t seed = 0;   // for this trial's stimulus details and perceptual noise
    // The same for all of a participant's trials: draws who the simulated person is (the feel
    // hand's own parameters, participants/person.hpp), apart from the trials' noise.
    std::uint64_t person = 0;
};

// A participant's `person` seed under the run's seed (plan_trials and the adaptive plans).
std::uint64_t person_seed(std::uint64_t seed, std::uint64_t participant);

// `participant` numbers participants 1, 2, ... (simulated) or hashes a human's id.
std::vector<std::vector<PlannedTrial>> plan_trials(const Protocol& p, std::uint64_t seed, std::uint64_t participant);

}  // namespace contactlab::experiments
