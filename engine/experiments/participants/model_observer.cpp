// model_observer.cpp — the model observer's answers (model_observer.hpp).
#include "engine/experiments/participants/model_observer.hpp"

#include "engine/experiments/protocol/grading.hpp"
#include "engine/experiments/base/random_stream.hpp"
#include "engine/experiments/base/results_table.hpp"

#include <cmath>
#include <sstream>

namespace contactlab::experiments {

ObserverSpec parse_observer(const std::string& spec) {
    ObserverSpec o;
    o.text = spec;
    const std::size_t colon = spec.find(':');
    const std::string fn = spec.substr(0, colon);
    if (!parse_psy_function(fn, o.function))
        throw ExperimentError("observer \"" + spec + "\": expected logistic, weibull or cumulative-normal before the ':', got \"" + fn + "\"");
    if (colon == std::string::npos) throw ExperimentError("observer \"" + spec + "\": give threshold=T,scale=S after the function");
    bool have_t = false, have_s = false;
    std::stringstream items(spec.substr(colon + 1));
    for (std::string item; std::getline(items, item, ',');) {
        const std::size_t eq = item.find('=');
        const std::string key = item.substr(0, eq);
        double v = 0.0;
        if (eq == std::string::npos || parse_number(item.substr(eq + 1), v) != NumberParse::ok)
            throw ExperimentError("observer \"" + spec + "\": \"" + item + "\" is not KEY=NUMBER");
        if (key == "threshold") o.threshold = v, have_t = true;
        else if (key == "scale") o.scale = v, have_s = true;
        else if (key == "guess") o.guess = v;
        else if (key == "lapse") o.lapse = v;
        else throw ExperimentError("observer \"" + spec + "\": unknown key \"" + key + "\" (threshold, scale, guess, lapse)");
    }
    if (!have_t || !have_s) throw ExperimentError("observer \"" + spec + "\": threshold and scale are required");
    if (!(o.scale > 0.0)) throw ExperimentError("observer \"" + spec + "\": scale must be above 0");
    if (o.function == PsyFunction::weibull && !(o.threshold > 0.0)) throw ExperimentError("observer \"" + spec + "\": a Weibull threshold must be above 0");
    if (!(o.guess >= 0.0 && o.lapse >= 0.0 && o.guess + o.lapse < 1.0))
        throw ExperimentError("observer \"" + spec + "\": guess and lapse must be at least 0 with guess + lapse below 1");
    return o;
}

TrialOutcome observe_trial(const Protocol& p, const ObserverSpec& o, const PlannedTrial& t) {
    if (p.answers.empty()) throw ExperimentError(p.origin + ": the model observer answers judgement tasks; " + to_string(p.task) + " is timed");
    std::uint64_t rng = mix64(t.seed ^ 0x0B5E4E4ull);
    const bool right = uniform01(rng) < psy_p(o.function, t.stimulus, o.threshold, o.scale, o.guess, o.lapse);
    // The right answer for this trial, then (if wrong) one of the others at random.
    std::string correct;
    for (const std::string& a : p.answers)
        if (graded_correct(p, t, a)) correct = a;
    TrialOutcome out;
    if (right || correct.empty()) {
        out.response = correct.empty() ? p.answers.front() : correct;
    } else {
        std::vector<const std::string*> others;
        for (const std::string& a : p.answers)
            if (a != correct) others.push_back(&a);
        out.response = *others[static_cast<std::size_t>(uniform01(rng) * static_cast<double>(others.size())) % others.size()];
    }
    out.correct = graded_correct(p, t, out.response);
    out.time_s = NAN;
    out.touched = true;  // nothing to touch: the answer is not for want of contact
    return out;
}

}  // namespace contactlab::experiments
