// quest_plus.hpp — QUEST+ (Watson 2017, "QUEST+: A general multidimensional Bayesian adaptive
// psychometric method", Journal of Vision 17(3):10): a posterior over the psychometric
// function's threshold, scale and lapse on grids (uniform prior), updated by Bayes' rule after
// each answer; the next stimulus is the candidate whose answer is expected to leave the least
// entropy in the posterior. The estimate is the threshold at the joint posterior's mode, as
// Watson reports it (on the threshold grid); the threshold's 95 % credible interval, from its
// marginal's quantiles, can stop the run when narrow enough.
#pragma once

#include "engine/experiments/protocol/protocol.hpp"

#include <vector>

namespace contactlab::experiments {

class QuestPlus {
public:
    explicit QuestPlus(const Procedure& p);

    double next() const { return next_; }
    void update(double x, bool correct);
    bool finished() const;
    double estimate() const;  // the threshold at the posterior's mode
    // The threshold's 95 % credible interval.
    void interval(double& lo, double& hi) const;
    int trials() const { return trials_; }

private:
    void choose();
    std::size_t level_index(double x) const;

    Procedure p_;
    std::vector<double> thresholds_, scales_, lapses_, levels_;
    std::vector<double> posterior_;  // thresholds x scales x lapses, normalised
    std::vector<double> p_correct_;  // levels x parameters: the likelihood table
    double next_ = 0.0;
    int trials_ = 0;
};

}  // namespace contactlab::experiments
