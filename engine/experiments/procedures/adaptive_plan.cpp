// adaptive_plan.cpp — interleaved adaptive procedures for one participant (adaptive_plan.hpp).
#include "engine/experiments/procedures/adaptive_plan.hpp"
#include "engine/experiments/base/random_stream.hpp"

namespace contactlab::experiments {

bool AdaptivePlan::Track::finished() const {
    if (invalid > max_trials) return true;  // a stimulus that always faults cannot go on for ever
    return stair ? stair->finished() : quest->finished();
}

AdaptivePlan::AdaptivePlan(const Protocol& p, std::uint64_t seed, std::uint64_t participant)
    : p_(p), state_(mix64(seed ^ mix64(participant) ^ 0xADA9ull)), base_(mix64(state_)), person_(person_seed(seed, participant)) {
    for (std::size_t c = 0; c < p.conditions.size(); ++c) {
        Track t;
        if (p.procedure.type == ProcedureType::staircase) t.stair = std::make_unique<Staircase>(p.procedure), t.max_trials = p.procedure.max_trials;
        else t.quest = std::make_unique<QuestPlus>(p.procedure), t.max_trials = p.procedure.trials;
        tracks_.push_back(std::move(t));
    }
}

bool AdaptivePlan::done() const {
    for (const Track& t : tracks_)
        if (!t.finished()) return false;
    return true;
}

const PlannedTrial& AdaptivePlan::next() {
    if (have_pending_) return pending_;
    std::vector<int> open;
    for (std::size_t c = 0; c < tracks_.size(); ++c)
        if (!tracks_[c].finished()) open.push_back(static_cast<int>(c));
    const int c = open.at(static_cast<std::size_t>(uniform01(state_) * static_cast<double>(open.size())) % open.size());
    Track& t = tracks_[static_cast<std::size_t>(c)];
    pending_ = PlannedTrial{};
    pending_.condition = c;
    pending_.trial = t.presented + 1;
    pending_.warmup = t.practised < p_.warmup;
    pending_.stimulus = pending_.warmup ? p_.procedure.hi : t.next();
    pending_.seed = mix64(base_ ^ (static_cast<std::uint64_t>(c) << 32) ^ static_cast<std::uint64_t>(pending_.trial));
    pending_.person = person_;
    have_pending_ = true;
    return pending_;
}

AdaptivePlan::Recorded AdaptivePlan::record(bool valid, bool correct) {
    Track& t = tracks_[static_cast<std::size_t>(pending_.condition)];
    have_pending_ = false;
    ++t.presented;
    Recorded r;
    if (pending_.warmup) {
        ++t.practised;  // practice counts whether or not it was valid: it is not analysed
    } else if (!valid) {
        ++t.invalid;
    } else if (t.stair) {
        r.reversal = t.stair->update(correct);
    } else {
        t.quest->update(pending_.stimulus, correct);
    }
    r.estimate = estimate(pending_.condition);
    return r;
}

std::size_t AdaptivePlan::max_trials() const {
    std::size_t n = 0;
    for (const Track& t : tracks_) n += static_cast<std::size_t>(p_.warmup + 2 * t.max_trials + 1);
    return n;
}

double AdaptivePlan::estimate(int condition) const {
    const Track& t = tracks_.at(static_cast<std::size_t>(condition));
    if (t.stair) return t.stair->estimate();
    return t.quest->trials() > 0 ? t.quest->estimate() : NAN;
}

}  // namespace contactlab::experiments
