// adaptive_plan.hpp — one participant's trials under an adaptive procedure (staircase or
// QUEST+): one procedure per condition, interleaved (each trial's condition drawn at random
// among those not finished, so a participant cannot follow one track), each condition's first
// `warmup` trials practice at the easy end (the largest stimulus), not fed to the procedure.
// The next stimulus depends on the answers so far, so the plan is rebuilt on resume by
// replaying the stored answers through record(): the same seed and answers give the same
// trials. An invalid trial is not fed to the procedure (its stimulus is presented again); at
// most as many invalid trials as the procedure's maximum keep a condition going.
//
// Room engine/experiments/procedures/: how the stimulus of the next trial is chosen: the staircase, QUEST+ and the
// adaptive plan that steps them (here). Includes protocol/ and base/.
// The rooms and their arrows: docs/ARCHITECTURE.md, "The experiments' rooms".
#pragma once

#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/procedures/quest_plus.hpp"
#include "engine/experiments/procedures/staircase.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"

#include <memory>
#include <vector>

namespace contactlab::experiments {

class AdaptivePlan {
public:
    AdaptivePlan(const Protocol& p, std::uint64_t seed, std::uint64_t participant);

    bool done() const;
    // The next trial; the same until record() is called.
    const PlannedTrial& next();
    struct Recorded {
        bool reversal = false;
        double estimate = NAN;
    };
    Recorded record(bool valid, bool correct);

    // Per condition: the procedure's estimate, reversals and trials fed to it.
    double estimate(int condition) const;
    // The most trials the plan can present (practice, the procedures' limits and as many repeats
    // of invalid trials): a live session's "of N" until the procedures stop, usually earlier.
    std::size_t max_trials() const;

private:
    struct Track {
        std::unique_ptr<Staircase> stair;
        std::unique_ptr<QuestPlus> quest;
        int presented = 0, practised = 0, invalid = 0;
        bool finished() const;
        double next() const { return stair ? stair->next() : quest->next(); }
        int max_trials = 0;
    };
    const Protocol& p_;
    std::uint64_t state_, base_;
    std::uint64_t person_;  // PlannedTrial::person for every trial of this participant
    std::vector<Track> tracks_;
    PlannedTrial pending_;
    bool have_pending_ = false;
};

}  // namespace contactlab::experiments
