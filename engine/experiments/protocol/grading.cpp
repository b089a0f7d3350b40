// grading.cpp — the right answer to a trial (grading.hpp).
#include "engine/experiments/protocol/grading.hpp"

namespace contactlab::experiments {

const std::string& sharper_answer(const Protocol& p, const PlannedTrial& t) {
    return p.answers.at(static_cast<std::size_t>(2 - comparison_interval(t.seed)));  // the reference's interval
}

bool graded_correct(const Protocol& p, const PlannedTrial& t, const std::string& response) {
    if (p.answers.empty() || response.empty()) return false;
    if (p.task == Task::surface_orientation) return response == p.answers[static_cast<std::size_t>(orientation_template(t.stimulus))];
    if (p.task == Task::edge_sharpness) return response == sharper_answer(p, t);
    return response == stimulus_label(p, t.stimulus);
}

}  // namespace contactlab::experiments
