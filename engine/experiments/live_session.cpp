// live_session.cpp — live trials, row-by-row results and resuming (live_session.hpp).
#include "engine/experiments/live_session.hpp"

#include "engine/experiments/results_row.hpp"
#include "engine/experiments/results_table.hpp"
#include "engine/experiments/stimulus.hpp"
#include "haptics/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>

namespace contactlab::experiments {

LiveSession::LiveSession(Protocol protocol, std::string participant, std::uint64_t seed, std::string results_path)
    : protocol_(std::move(protocol)), participant_(std::move(participant)), results_path_(std::move(results_path)) {
    if (participant_.empty() || participant_.find_first_of(",\"\n\r") != std::string::npos)
        throw ExperimentError("--participant: an id without commas, quotes or line breaks, e.g. P07");
    // A live session presents one stimulus per trial from a fixed plan: two intervals per trial
    // (edge sharpness) and stimuli chosen from the answers (staircase, QUEST+) are batch-only
    // for now. Refused here, clearly, rather than run wrongly.
    if (protocol_.task == Task::edge_sharpness || protocol_.procedure.type != ProcedureType::constant)
        throw ExperimentError(protocol_.origin + ": live sessions run constant-stimuli protocols with one stimulus per trial; "
                              "two-interval tasks (edge-sharpness) and adaptive procedures run with `contactlab experiment run`");
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
        const std::size_t who = *t.column("participant"), cond = *t.column("condition"), num = *t.column("trial"),
                          valid = *t.column("valid");
        std::map<std::pair<std::string, int>, bool> seen;  // (condition, trial) of this participant -> valid
        for (std::size_t i = 0; i < t.rows.size(); ++i) {
            lines_.push_back(csv_line(t.rows[i]));
            if (t.rows[i][who] != participant_) continue;
            seen[{t.rows[i][cond], static_cast<int>(t.number(i, num))}] = t.number(i, valid) != 0.0;
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
    Stimulus st = make_stimulus(protocol_, condition(), trial(), 0.0);
    scene_ = std::move(st.scene);
    small_bumps_ = st.small_bumps;
    large_bumps_ = st.large_bumps;
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
    TrialRecord rec;
    rec.participant = participant_;
    rec.trial = trial();
    rec.response = r.response;
    rec.touched = r.touched.value_or(r.peak_force > 0.0);
    // An answer about a stimulus the finger never touched says nothing of the display: the trial
    // is invalid (left out of the analysis) and, like a faulted one, presented again when the
    // protocol's repeat_invalid says so.
    rec.valid = r.valid && rec.touched;
    rec.failed = protocol_.task == Task::contour_following && r.contact_breaks > 0;
    rec.time_s = r.time_s;
    rec.contact_breaks = r.contact_breaks;
    rec.peak_force = r.peak_force;
    rec.device = r.device;
    rec.small_bumps = small_bumps_;
    rec.large_bumps = large_bumps_;
    const std::vector<std::string> row = results_row(protocol_, rec);
    lines_.push_back(csv_line(row));
    write();  // the row is on disk before the next trial starts
    if (!rec.valid) queue_repeat();
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
