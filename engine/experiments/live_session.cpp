// live_session.cpp — live trials, row-by-row results and resuming (live_session.hpp).
#include "engine/experiments/live_session.hpp"

#include "engine/experiments/experiment_run.hpp"
#include "engine/experiments/results_table.hpp"
#include "engine/experiments/sim_participant.hpp"
#include "engine/experiments/stimulus.hpp"
#include "haptics/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>

namespace contactlab::experiments {
namespace {

std::string fmt(double v, const char* f) {
    char buf[48];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

}  // namespace

LiveSession::LiveSession(Protocol protocol, std::string participant, std::uint64_t seed, std::string results_path)
    : protocol_(std::move(protocol)), participant_(std::move(participant)), results_path_(std::move(results_path)) {
    if (participant_.empty() || participant_.find_first_of(",\"\n\r") != std::string::npos)
        throw ExperimentError("--participant: an id without commas, quotes or line breaks, e.g. P07");
    // A person's id numbers the trial order as a simulated participant's number does.
    // FNV-1a: the same number for the same id on any machine (std::hash promises no such thing).
    std::uint64_t number = 0xcbf29ce484222325ull;
    for (const unsigned char ch : participant_) number = (number ^ ch) * 0x100000001b3ull;
    for (const auto& block : plan_trials(protocol_, seed, number)) {
        queue_.insert(queue_.end(), block.begin(), block.end());
        block_end_.push_back(queue_.size());
    }
    const std::vector<std::string>& columns = results_columns(protocol_);
    lines_.push_back(csv_line(columns));
    if (std::filesystem::exists(results_path_)) {
        const ResultsTable t = read_results_csv(results_path_);
        if (t.columns != columns)
            throw ExperimentError(results_path_ + ": its columns are not this protocol's results columns (" + lines_[0] + ")");
        std::map<std::pair<std::string, int>, bool> seen;  // (condition, trial) of this participant -> valid
        for (std::size_t i = 0; i < t.rows.size(); ++i) {
            lines_.push_back(csv_line(t.rows[i]));
            if (t.rows[i][0] != participant_) continue;
            seen[{t.rows[i][1], static_cast<int>(t.number(i, 2))}] = t.number(i, 6) != 0.0;
        }
        // Done trials are those already in the file (their repeats queued again): skip them.
        for (auto it = seen.end(); next_ < queue_.size() && (it = seen.find({condition().name, queue_[next_].trial})) != seen.end();) {
            if (!it->second) queue_repeat();
            ++next_;
        }
        resumed_ = next_;
    }
    if (!finished()) build_scene();
}

const Condition& LiveSession::condition() const {
    return protocol_.conditions.at(static_cast<std::size_t>(queue_.at(next_).condition));
}

void LiveSession::build_scene() {
    // The live trial is felt as the simulated participant's first run is: the same scene.
    scene_ = make_stimulus(protocol_, condition(), trial(), 0.0).scene;
    ++version_;
}

void LiveSession::write() {
    std::string text;
    for (const std::string& l : lines_) text += l + "\n";
    write_file_atomically(results_path_, text);
}

void LiveSession::answer(const LiveTrialResult& r) {
    if (finished()) throw ExperimentError("the experiment is finished");
    const bool judged = !protocol_.answers.empty();
    if (judged && std::find(protocol_.answers.begin(), protocol_.answers.end(), r.response) == protocol_.answers.end()) {
        std::string set;
        for (const std::string& a : protocol_.answers) {
            if (!set.empty()) set += ", ";
            set += a;
        }
        throw ExperimentError("answer \"" + r.response + "\" is not one of " + set);
    }
    const PlannedTrial t = trial();
    const Condition& c = condition();
    bool correct = false;
    if (protocol_.task == Task::surface_orientation)
        correct = r.response == (t.stimulus < 90.0 ? protocol_.answers.front() : protocol_.answers.back());
    else if (judged)
        correct = r.response == stimulus_label(protocol_, t.stimulus);
    std::vector<std::string> row = {participant_,
                                    c.name,
                                    std::to_string(t.trial),
                                    stimulus_label(protocol_, t.stimulus),
                                    r.response,
                                    judged ? (correct ? "1" : "0") : "",
                                    r.valid ? "1" : "0",
                                    t.warmup ? "1" : "0",
                                    fmt(r.time_s, "%.4f"),
                                    "0",
                                    std::to_string(r.contact_breaks),
                                    fmt(r.peak_force, "%.4f"),
                                    c.contact_location ? "1" : "0"};
    if (protocol_.task == Task::contour_following && r.contact_breaks > 0) row[9] = std::string("1");  // failed
    if (protocol_.task == Task::surface_orientation) {
        row.push_back(fmt(c.eccentricity, "%g"));
        row.push_back(fmt(c.total_stiffness * 1e-3, "%g"));
    }
    if (protocol_.task == Task::curvature) row.push_back(c.motion);
    lines_.push_back(csv_line(row));
    write();  // the row is on disk before the next trial starts
    if (!r.valid) queue_repeat();
    ++next_;
    if (!finished()) build_scene();
}

void LiveSession::queue_repeat() {
    const PlannedTrial t = trial();
    if (!t.warmup && protocol_.repeat_invalid) {
        // Presented again at the end of its block.
        const std::size_t block = static_cast<std::size_t>(
            std::upper_bound(block_end_.begin(), block_end_.end(), next_) - block_end_.begin());
        PlannedTrial again = t;
        again.seed = mix64(t.seed);
        int last = 0;
        for (std::size_t i = block ? block_end_[block - 1] : 0; i < block_end_[block]; ++i) last = std::max(last, queue_[i].trial);
        again.trial = last + 1;
        queue_.insert(queue_.begin() + static_cast<std::ptrdiff_t>(block_end_[block]), again);
        for (std::size_t b = block; b < block_end_.size(); ++b) ++block_end_[b];
    }
}

}  // namespace contactlab::experiments
