// experiment_run.cpp — protocol -> trials -> simulated participant -> results file
// (experiment_run.hpp).
#include "engine/experiments/experiment_run.hpp"

#include "engine/experiments/results_table.hpp"
#include "engine/experiments/sim_participant.hpp"
#include "engine/experiments/trial_plan.hpp"
#include "haptics/atomic_file.hpp"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <thread>

namespace contactlab::experiments {
namespace {

std::string fmt(double v, const char* f = "%.6g") {
    if (!std::isfinite(v)) return "";
    char buf[48];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

struct ParticipantRun {
    std::vector<std::vector<std::string>> rows;
    std::size_t invalid = 0, warmup = 0;
};

std::string trace_csv(const TrialOutcome& o) {
    std::string s = "t,x,y,phi,contact,fx,fy,roller_l,l_d\n";
    char line[256];
    for (const drivers::TickRecord& r : o.shown) {
        std::snprintf(line, sizeof line, "%.4f,%.6g,%.6g,%.6g,%d,%.6g,%.6g,%.6g,%.6g\n", r.t, r.finger.x, r.finger.y, r.phi,
                      r.contact ? 1 : 0, r.force.x, r.force.y, r.roller_l, r.l_d);
        s += line;
    }
    return s;
}

ParticipantRun run_participant(const Protocol& p, const RunOptions& o, std::uint64_t participant, const std::string& trace_dir,
                               std::atomic<std::size_t>& done, std::size_t total) {
    ParticipantRun out;
    const std::string id = "sim" + std::to_string(participant);
    for (std::vector<PlannedTrial> block : plan_trials(p, o.seed, participant)) {
        const std::size_t planned = block.size();
        for (std::size_t i = 0; i < block.size(); ++i) {
            PlannedTrial t = block[i];
            const Condition& c = p.conditions[static_cast<std::size_t>(t.condition)];
            TrialOutcome r = perform_sim_trial(p, t);
            // At most as many repeats as planned trials: a stimulus that always faults the servo
            // cannot keep the block going for ever.
            // A warm-up trial is not analysed, so it is not repeated either.
            if (!r.valid && !t.warmup && p.repeat_invalid && block.size() < 2 * planned) {
                PlannedTrial again = t;
                again.seed = mix64(t.seed);
                again.trial = static_cast<int>(block.size()) + 1;
                block.push_back(again);  // presented again at the end of the block
            }
            out.invalid += !r.valid;
            out.warmup += t.warmup;
            std::vector<std::string> row = {id,
                                            c.name,
                                            std::to_string(t.trial),
                                            stimulus_label(p, t.stimulus),
                                            r.response,
                                            r.response.empty() ? "" : (r.correct ? "1" : "0"),
                                            r.valid ? "1" : "0",
                                            t.warmup ? "1" : "0",
                                            fmt(r.time_s, "%.4f"),
                                            r.failed ? "1" : "0",
                                            std::to_string(r.contact_breaks),
                                            fmt(r.peak_force, "%.4f"),
                                            c.contact_location ? "1" : "0"};
            if (p.task == Task::surface_orientation) {
                row.push_back(fmt(c.eccentricity));
                row.push_back(fmt(c.total_stiffness * 1e-3));  // N/mm, as seed 004 writes k
            }
            if (p.task == Task::curvature) row.push_back(c.motion);
            if (!trace_dir.empty())
                write_file_atomically(trace_dir + "/" + id + "-" + c.name + "-" + std::to_string(t.trial) + ".csv", trace_csv(r));
            out.rows.push_back(std::move(row));
            if (o.progress) o.progress(++done, total);
        }
    }
    return out;
}

}  // namespace

const std::vector<std::string>& results_columns(const Protocol& p) {
    static const std::vector<std::string> base = {"participant", "condition", "trial",  "stimulus",       "response",
                                                  "correct",     "valid",     "warmup", "time_s",         "failed",
                                                  "contact_breaks", "peak_force_n", "contact_location"};
    static const std::vector<std::string> orientation = [] {
        auto v = base;
        v.push_back("e");
        v.push_back("k");
        return v;
    }();
    static const std::vector<std::string> curvature = [] {
        auto v = base;
        v.push_back("motion");
        return v;
    }();
    return p.task == Task::surface_orientation ? orientation : p.task == Task::curvature ? curvature : base;
}

RunSummary run_experiment(const Protocol& p, const RunOptions& o) {
    if (o.participants.empty()) throw ExperimentError("no participants");
    if (o.output.empty()) throw ExperimentError("no output file");
    std::string trace_dir;
    if (o.traces) {
        trace_dir = o.output + ".traces";
        std::filesystem::create_directories(trace_dir);
    }
    std::size_t per_participant = 0;
    for (const auto& block : plan_trials(p, o.seed, 1)) per_participant += block.size();
    const std::size_t total = per_participant * o.participants.size();
    std::atomic<std::size_t> done{0}, next{0};
    std::vector<ParticipantRun> runs(o.participants.size());
    std::mutex error_lock;
    std::string error;
    auto worker = [&] {
        for (std::size_t i; (i = next++) < runs.size();) {
            try {
                runs[i] = run_participant(p, o, o.participants[i], trace_dir, done, total);
            } catch (const std::exception& e) {
                std::lock_guard<std::mutex> g(error_lock);
                error = e.what();
            }
        }
    };
    const int jobs = std::max(1, std::min<int>(o.jobs, static_cast<int>(runs.size())));
    std::vector<std::thread> threads;
    for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
    worker();
    for (std::thread& t : threads) t.join();
    if (!error.empty()) throw ExperimentError(error);

    std::string csv = csv_line(results_columns(p)) + "\n";
    RunSummary sum;
    for (const ParticipantRun& r : runs) {
        for (const auto& row : r.rows) csv += csv_line(row) + "\n";
        sum.rows += r.rows.size();
        sum.invalid += r.invalid;
        sum.warmup += r.warmup;
    }
    write_file_atomically(o.output, csv);
    return sum;
}

}  // namespace contactlab::experiments
