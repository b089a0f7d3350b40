// live_session.cpp — live trials, row-by-row results and resuming (live_session.hpp).
#include "engine/experiments/runs/live_session.hpp"

#include "engine/experiments/runs/results_row.hpp"
#include "engine/experiments/base/path_name.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/protocol/stimulus.hpp"
#include "engine/experiments/base/random_stream.hpp"
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
    // The id names the default results file (PROTOCOL-ID.csv, the editor's): no path in it.
    if (const std::string why = path_name_problem(participant_); !why.empty())
        throw ExperimentError("--participant: the id " + why + " (it is part of a file name), e.g. P07, got \"" +
                              escaped_name(participant_) + "\"");
    // A person's id numbers the trial order as a simulated participant's number does.
    // FNV-1a: the same number for the same id on any machine (std::hash promises no such thing).
    std::uint64_t number = 0xcbf29ce484222325ull;
    for (const unsigned char ch : participant_) number = (number ^ ch) * 0x100000001b3ull;
    if (protocol_.procedure.type != ProcedureType::constant) {
        plan_ = std::make_unique<AdaptivePlan>(protocol_, seed, number);
    } else {
        for (const auto& block : plan_trials(protocol_, seed, number)) {
            queue_.insert(queue_.end(), block.begin(), block.end());
            block_end_.push_back(queue_.size());
        }
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
        const std::size_t correct = *t.column("correct");
        for (std::size_t i = 0; i < t.rows.size(); ++i) {
            lines_.push_back(csv_line(t.rows[i]));
            if (t.rows[i][who] != participant_) continue;
            seen[{t.rows[i][cond], static_cast<int>(t.number(i, num))}] = t.number(i, valid) != 0.0;
            if (plan_) {
                // Replayed in order through the procedure: the next stimulus depends on them.
                if (plan_->done())
                    throw ExperimentError(results_path_ + ": line " + std::to_string(i + 2) + ": " + participant_ +
                                          " has more rows than the procedure presents (the file is not this session's)");
                const PlannedTrial& want = plan_->next();
                const std::string name = protocol_.conditions.at(static_cast<std::size_t>(want.condition)).name;
                if (t.rows[i][cond] != name || static_cast<int>(t.number(i, num)) != want.trial)
                    throw ExperimentError(results_path_ + ": line " + std::to_string(i + 2) + ": " + participant_ + "'s " +
                                          t.rows[i][cond] + " trial " + t.rows[i][num] + " is not the procedure's next (" + name +
                                          " trial " + std::to_string(want.trial) + "): the file is not this session's");
                plan_->record(t.number(i, valid) != 0.0, t.number(i, correct) != 0.0);
                ++adaptive_done_;
            }
        }
        // Done trials are those already in the file (their repeats queued again): skip them.
        for (auto it = seen.end(); !plan_ && next_ < queue_.size() && (it = seen.find({condition().name, queue_[next_].trial})) != seen.end();) {
            if (!it->second) queue_repeat();
            ++next_;
        }
        resumed_ = done();
    }
    if (plan_ && !plan_->done()) current_ = plan_->next();
    if (!finished()) build_scene();
}

std::size_t LiveSession::total() const {
    if (!plan_) return queue_.size();
    return plan_->done() ? adaptive_done_ : std::max(plan_->max_trials(), adaptive_done_ + 1);
}

bool LiveSession::next_interval() {
    if (finished() || interval_ >= intervals()) return false;
    ++interval_;
    build_scene();
    return true;
}

const Condition& LiveSession::condition() const {
    return protocol_.conditions.at(static_cast<std::size_t>(trial().condition));
}

std::optional<drivers::FingerSweep> LiveSession::sweep() const {
    if (protocol_.task != Task::curvature || finished()) return std::nullopt;
    drivers::FingerSweep s;
    s.x0 = curvature_slide_start(protocol_, condition());
    s.x1 = -s.x0;
    s.speed = protocol_.hand_speed;
    s.finger_radius = protocol_.finger_radius;
    s.press = protocol_.hand_press;
    s.chord = protocol_.chord;
    s.height = trial().stimulus;
    return s;
}

void LiveSession::build_scene() {
    // The live trial is felt as the simulated participant's first run is: the same scene (a
    // two-interval trial's edge in the interval shown).
    Stimulus st = protocol_.task == Task::edge_sharpness ? make_edge_stimulus(protocol_, edge_radius(protocol_, trial(), interval_))
                                                          : make_stimulus(protocol_, condition(), trial(), 0.0);
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
    if (interval_ < intervals())
        throw ExperimentError("feel edge " + std::to_string(interval_ + 1) + " of " + std::to_string(intervals()) +
                              " first (Next), then answer which felt sharper");
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
    rec.contact_fraction = r.contact_fraction;
    rec.peak_force = r.peak_force;
    rec.device = r.device;
    rec.small_bumps = small_bumps_;
    rec.large_bumps = large_bumps_;
    if (plan_) {
        // The procedure's answer to this trial (its reversal and estimate go into the row); the
        // row's own grading says whether it was right.
        const std::vector<std::string> graded = results_row(protocol_, rec);
        const auto& columns = results_columns(protocol_);
        const std::size_t correct_col = static_cast<std::size_t>(std::find(columns.begin(), columns.end(), "correct") - columns.begin());
        const AdaptivePlan::Recorded a = plan_->record(rec.valid, graded.at(correct_col) == "1");
        rec.reversal = a.reversal;
        rec.estimate = a.estimate;
    }
    const std::vector<std::string> row = results_row(protocol_, rec);
    lines_.push_back(csv_line(row));
    write();  // the row is on disk before the next trial starts
    if (plan_) {
        ++adaptive_done_;
        if (!plan_->done()) current_ = plan_->next();
    } else {
        if (!rec.valid) queue_repeat();
        ++next_;
    }
    interval_ = 1;
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
