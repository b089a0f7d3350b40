// results_row.cpp — a trial's cells (results_row.hpp).
#include "engine/experiments/runs/results_row.hpp"

#include "engine/experiments/protocol/grading.hpp"

#include <cmath>
#include <cstdio>
#include <mutex>

namespace contactlab::experiments {
namespace {

std::string fmt(double v, const char* f = "%.6g") {
    if (!std::isfinite(v)) return "";
    char buf[48];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

std::vector<std::string> with(std::vector<std::string> v, std::initializer_list<const char*> more) {
    v.insert(v.end(), more.begin(), more.end());
    return v;
}

}  // namespace

const std::vector<std::string>& results_columns(const Protocol& p) {
    static const std::vector<std::string> base = {
        "participant", "condition", "trial",        "stimulus",     "stimulus_unit", "response", "correct", "valid",
        "warmup",      "time_s",    "failed",       "contact_breaks", "contact_fraction", "peak_force_n", "touched",
        "contact_location", "device"};
    static const std::vector<std::string> orientation = with(base, {"e", "k"});
    static const std::vector<std::string> curvature = with(base, {"motion"});
    static const std::vector<std::string> bumps = with(base, {"small_bumps", "large_bumps"});
    static const std::vector<std::string> edge = with(base, {"reference_mm", "comparison_interval"});
    static const std::vector<std::string> adaptive_columns = {"procedure", "target_p", "reversal", "estimate"};
    const std::vector<std::string>* task = &base;
    switch (p.task) {
        case Task::surface_orientation: task = &orientation; break;
        case Task::curvature: task = &curvature; break;
        case Task::bump_counting: task = &bumps; break;
        case Task::edge_sharpness: task = &edge; break;
        case Task::contour_following: break;
    }
    if (p.procedure.type == ProcedureType::constant) return *task;
    // The adaptive tables: the task's columns and the procedure's, built once per task.
    static std::vector<std::string> built[5];
    static std::once_flag once[5];
    const auto i = static_cast<std::size_t>(p.task);
    std::call_once(once[i], [&] {
        built[i] = *task;
        built[i].insert(built[i].end(), adaptive_columns.begin(), adaptive_columns.end());
    });
    return built[i];
}

std::vector<std::string> results_row(const Protocol& p, const TrialRecord& r) {
    const Condition& c = p.conditions.at(static_cast<std::size_t>(r.trial.condition));
    std::vector<std::string> row = {r.participant,
                                    c.name,
                                    std::to_string(r.trial.trial),
                                    stimulus_label(p, r.trial.stimulus),
                                    stimulus_unit(p.task),
                                    r.response,
                                    r.response.empty() ? "" : (graded_correct(p, r.trial, r.response) ? "1" : "0"),
                                    r.valid ? "1" : "0",
                                    r.trial.warmup ? "1" : "0",
                                    fmt(r.time_s, "%.4f"),
                                    r.failed ? "1" : "0",
                                    std::to_string(r.contact_breaks),
                                    fmt(r.contact_fraction, "%.4f"),
                                    fmt(r.peak_force, "%.4f"),
                                    r.touched ? "1" : "0",
                                    c.contact_location ? "1" : "0",
                                    r.device};
    switch (p.task) {
        case Task::surface_orientation:
            row.push_back(fmt(c.eccentricity));
            row.push_back(fmt(c.total_stiffness * 1e-3));  // N/mm, as seed 004 writes k
            break;
        case Task::curvature: row.push_back(c.motion); break;
        case Task::bump_counting:
            row.push_back(std::to_string(r.small_bumps));
            row.push_back(std::to_string(r.large_bumps));
            break;
        case Task::edge_sharpness:
            row.push_back(fmt(p.reference_radius * 1e3));
            row.push_back(std::to_string(comparison_interval(r.trial.seed)));
            break;
        case Task::contour_following: break;
    }
    if (p.procedure.type != ProcedureType::constant) {
        row.push_back(p.procedure.label());
        row.push_back(fmt(p.procedure.target_p(), "%.4f"));
        row.push_back(r.reversal ? "1" : "0");
        row.push_back(fmt(r.estimate));
    }
    return row;
}

}  // namespace contactlab::experiments
