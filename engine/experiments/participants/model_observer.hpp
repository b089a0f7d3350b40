// model_observer.hpp — a model observer (`--participant observer:logistic:threshold=T,...`):
// a participant who feels nothing and answers each trial right with probability
// p(correct) = guess + (1 - guess - lapse) F(x) (psychometric.hpp), x the trial's stimulus in
// the protocol's units. It goes through the same trial machinery as the simulated participant
// (plans, procedures, durable rows, resume), so procedures and fits are tested end to end
// against a known truth. Its random stream comes from the trial's seed, which depends on the
// run's seed and the participant's number: observers 1..10 answer independently.
#pragma once

#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/protocol/psychometric.hpp"
#include "engine/experiments/participants/trial_outcome.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"

#include <string>

namespace contactlab::experiments {

struct ObserverSpec {
    PsyFunction function = PsyFunction::logistic;
    double threshold = 1.0, scale = 1.0, guess = 0.5, lapse = 0.0;
    std::string text;  // as given: "logistic:threshold=2,scale=0.4,guess=0.5,lapse=0.02"
};

// "FUNCTION:threshold=T,scale=S[,guess=G][,lapse=L]" (threshold and scale required; guess
// defaults to 0.5, lapse to 0). Throws ExperimentError saying what is wrong.
ObserverSpec parse_observer(const std::string& spec);

// The observer's answer to a trial: right with its p(correct); a wrong answer is another of
// the protocol's answers. Timed tasks (contour following) have no answer: refused.
TrialOutcome observe_trial(const Protocol& p, const ObserverSpec& o, const PlannedTrial& t);

}  // namespace contactlab::experiments
