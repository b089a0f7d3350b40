// trial_plan.cpp — reproducible trial orders (trial_plan.hpp).
#include "engine/experiments/protocol/trial_plan.hpp"

#include "engine/experiments/base/random_stream.hpp"

#include <cmath>
#include <numeric>
#include <utility>

namespace contactlab::experiments {

namespace {

std::size_t below(std::uint64_t& state, std::size_t n) {
    return static_cast<std::size_t>(uniform01(state) * static_cast<double>(n)) % n;
}

template <class T>
void shuffle(std::vector<T>& v, std::uint64_t& state) {
    for (std::size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[below(state, i)]);
}

}  // namespace

std::uint64_t person_seed(std::uint64_t seed, std::uint64_t participant) { return mix64(seed ^ mix64(participant) ^ 0x9E450Aull); }

std::vector<std::vector<PlannedTrial>> plan_trials(const Protocol& p, std::uint64_t seed, std::uint64_t participant) {
    std::uint64_t state = mix64(seed ^ mix64(participant));
    std::vector<int> order(p.conditions.size());
    std::iota(order.begin(), order.end(), 0);
    if (order.size() == 2) {
        if (participant % 2 == 0) std::swap(order[0], order[1]);  // participants 1, 3, ...: as written
    } else {
        shuffle(order, state);
    }
    std::vector<std::vector<PlannedTrial>> blocks;
    for (const int c : order) {
        std::vector<double> stimuli;
        if (p.trials > 0) {
            for (int i = 0; i < p.trials; ++i) stimuli.push_back(p.stimuli[below(state, p.stimuli.size())]);
        } else {
            for (int r = 0; r < p.repetitions; ++r) stimuli.insert(stimuli.end(), p.stimuli.begin(), p.stimuli.end());
            shuffle(stimuli, state);
        }
        std::vector<PlannedTrial> block;
        for (std::size_t i = 0; i < stimuli.size(); ++i) {
            PlannedTrial t;
            t.condition = c;
            t.trial = static_cast<int>(i) + 1;
            t.stimulus = stimuli[i];
            t.warmup = static_cast<int>(i) < p.warmup;
            t.seed = mix64(state ^ (static_cast<std::uint64_t>(c) << 32) ^ i);
            t.person = person_seed(seed, participant);
            block.push_back(t);
        }
        blocks.push_back(std::move(block));
    }
    return blocks;
}

}  // namespace contactlab::experiments
