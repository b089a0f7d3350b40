// experiment_run.cpp — protocol -> trials -> simulated participant -> results file, durable and
// resumable (experiment_run.hpp).
#include "engine/experiments/runs/experiment_run.hpp"

#include "engine/experiments/procedures/adaptive_plan.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/runs/run_files.hpp"
#include "engine/experiments/runs/run_meta.hpp"
#include "engine/experiments/participants/servo_trial.hpp"
#include "engine/experiments/participants/sim_participant.hpp"
#include "engine/experiments/base/trial_profile.hpp"
#include "engine/experiments/protocol/trial_plan.hpp"
#include "engine/experiments/participants/wearable_trial.hpp"
#include "engine/experiments/base/random_stream.hpp"
#include "engine/experiments/base/sha256.hpp"
#include "engine/experiments/protocol/grading.hpp"
#include "haptics/atomic_file.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

namespace contactlab::experiments {
namespace {

namespace fs = std::filesystem;

// The trial's trace: what the CLD rig displayed (finger, force, roller), or on the wearable
// platform its tilt, press force and cable tensions with the arc's slope under the contact.
std::string trace_csv(const TrialOutcome& o) {
    char line[256];
    if (!o.platform.empty()) {
        std::string s = "t,contact_x,surface_angle,tilt,force,q1,q2,q3,contact,fault\n";
        for (const drivers::sim::CurvatureSample& r : o.platform) {
            std::snprintf(line, sizeof line, "%.4f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d\n", r.t, r.contact_x, r.surface_angle,
                          r.platform_tilt, r.platform_force, r.tension(0), r.tension(1), r.tension(2), r.contact ? 1 : 0,
                          r.fault ? 1 : 0);
            s += line;
        }
        return s;
    }
    std::string s = "t,x,y,phi,contact,fx,fy,roller_l,l_d\n";
    for (const drivers::TickRecord& r : o.shown) {
        std::snprintf(line, sizeof line, "%.4f,%.6g,%.6g,%.6g,%d,%.6g,%.6g,%.6g,%.6g\n", r.t, r.finger.x, r.finger.y, r.phi,
                      r.contact ? 1 : 0, r.force.x, r.force.y, r.roller_l, r.l_d);
        s += line;
    }
    return s;
}

// One participant's run: the rows (CSV lines) in order, found on disk or performed.
struct ParticipantRun {
    std::vector<std::string> lines;
    std::size_t invalid = 0, warmup = 0, resumed = 0;
    bool finished = false;
};

// Shared by the workers: the rows so far, for RESULTS.csv whenever a participant finishes.
struct Shared {
    const Protocol& p;
    const RunOptions& o;
    const RunFiles& files;
    std::vector<ParticipantRun> runs;
    std::mutex lock;
    std::atomic<std::size_t> done{0};
    std::size_t total = 0;
    TrialProfile profile;  // the workers' profiles, added as each ends (RunOptions::profile)

    // RESULTS.csv with every participant finished so far, in participant order.
    void write_results(bool all) {
        std::string csv = csv_line(results_columns(p)) + "\n";
        for (const ParticipantRun& r : runs)
            if (all || r.finished)
                for (const std::string& l : r.lines) csv += l + "\n";
        write_file_atomically(o.output, csv);
    }
};

std::string participant_id(const RunOptions& o, std::uint64_t n) { return (o.observer ? "obs" : "sim") + std::to_string(n); }

constexpr const char* kObserverDevice = "model-observer";

// One trial performed: by the model observer, or by the simulated participant through the servo.
// Profiled, what the trial's stages did not take is the person's perception (trial_profile.hpp).
TrialOutcome perform(const Protocol& p, const RunOptions& o, const PlannedTrial& t) {
    TrialProfile* const profile = thread_profile();
    if (!profile) return o.observer ? observe_trial(p, *o.observer, t) : perform_sim_trial(p, t);
    const double before = profile->staged();  // s
    StageClock clock;
    clock.start(true);
    TrialOutcome r = o.observer ? observe_trial(p, *o.observer, t) : perform_sim_trial(p, t);
    double all = 0.0;  // ns
    clock.lap(all);
    profile->perception += all * 1e-9 - (profile->staged() - before);
    ++profile->trials;
    return r;
}

// Where a results column is (results_columns always has the ones asked for here).
std::size_t column_index(const std::vector<std::string>& columns, const char* name) {
    return static_cast<std::size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin());
}

// ---- a resume checks what it replays ----
// A participant's checksums (RunFiles::sums): per committed row, its own and its trace's SHA-256.
struct Ledger {
    bool present = false;
    std::vector<std::pair<std::string, std::string>> rows;  // (row sha256, trace sha256 or "-")
};

Ledger read_ledger(const std::string& path) {
    Ledger l;
    std::ifstream in(path, std::ios::binary);
    if (!in) return l;
    l.present = true;
    std::string row, trace;
    while (in >> row >> trace) l.rows.emplace_back(row, trace);
    return l;
}

// A row from an interrupted run, before it is replayed: graded as its stimulus and response say,
// the same bytes as when its trial was committed, and its trace there with the same bytes.
// Anything else: an edited or damaged run folder, refused rather than resumed from.
void verify_done_row(const Protocol& p, const RunOptions& o, const RunFiles& files, const std::string& id, std::size_t k,
                     const std::vector<std::string>& row, const std::string& line, const PlannedTrial& t, const Condition& c,
                     const Ledger& ledger) {
    const std::string part = files.part(id);
    const std::string which = part + ": row " + std::to_string(k + 1) + " (" + c.name + " trial " + std::to_string(t.trial) + ")";
    const std::string hint = "; give --overwrite to start again";
    const std::vector<std::string>& columns = results_columns(p);
    const std::string& response = row[column_index(columns, "response")];
    const std::string graded = response.empty() ? "" : (graded_correct(p, t, response) ? "1" : "0");
    if (row[column_index(columns, "correct")] != graded)
        throw ExperimentError(which + ": correct is \"" + row[column_index(columns, "correct")] + "\" but the response \"" + response +
                              "\" to stimulus " + row[column_index(columns, "stimulus")] + " grades \"" + graded + "\"" + hint);
    if (!ledger.present)
        throw ExperimentError(which + ": no checksums (" + files.sums(id) + " is missing), so the rows cannot be trusted" + hint);
    if (k >= ledger.rows.size())
        throw ExperimentError(which + ": not in " + files.sums(id) + " (a row this run did not commit)" + hint);
    if (sha256_hex(line) != ledger.rows[k].first)
        throw ExperimentError(which + ": not the row committed for that trial (its SHA-256 differs from " + files.sums(id) +
                              "): edited or damaged" + hint);
    if (!o.traces || o.observer) return;
    const std::string trace = files.trace(id, c.name, t.trial);
    if (!std::filesystem::exists(trace))
        throw ExperimentError(trace + ": missing, the trace of " + which + hint);
    if (sha256_hex(read_file_bytes(trace)) != ledger.rows[k].second)
        throw ExperimentError(trace + ": not the trace committed with " + which + " (its SHA-256 differs): edited or damaged" + hint);
}

// A new trial's trace on disk (before its row: a row on disk always has its trace); its SHA-256
// for the ledger, "-" when the run keeps no traces.
std::string commit_trace(const RunOptions& o, const RunFiles& files, const std::string& id, const Condition& c,
                         const PlannedTrial& t, const TrialOutcome& r) {
    if (!o.traces || o.observer) return "-";
    const StageTimer timer(&TrialProfile::files);
    const std::string trace = trace_csv(r);
    write_file_atomically(files.trace(id, c.name, t.trial), trace);
    return sha256_hex(trace);
}

TrialRecord record_of(const Protocol& p, const RunOptions& o, const std::string& id, const PlannedTrial& t, const TrialOutcome& r) {
    TrialRecord rec;
    rec.participant = id;
    rec.trial = t;
    rec.response = r.response;
    rec.valid = r.valid;
    rec.failed = r.failed;
    rec.time_s = r.time_s;
    rec.contact_breaks = r.contact_breaks;
    rec.contact_fraction = r.contact_fraction;
    rec.peak_force = r.peak_force;
    rec.touched = r.touched;
    rec.device = o.observer ? kObserverDevice : p.device.c_str();
    rec.small_bumps = r.small_bumps;
    rec.large_bumps = r.large_bumps;
    return rec;
}

// An adaptive procedure's participant: trials from an AdaptivePlan, replaying stored rows.
void run_adaptive_participant(Shared& sh, std::size_t index, const std::vector<std::vector<std::string>>& done_rows) {
    const Protocol& p = sh.p;
    const RunOptions& o = sh.o;
    ParticipantRun& out = sh.runs[index];
    const std::string id = participant_id(o, o.participants[index]);
    const std::string part = sh.files.part(id);
    const std::vector<std::string>& columns = results_columns(p);
    auto column = [&](const char* name) { return column_index(columns, name); };
    const std::size_t condition_col = column("condition"), trial_col = column("trial"), valid_col = column("valid"),
                      correct_col = column("correct"), stimulus_col = column("stimulus");
    std::string part_text = csv_line(columns) + "\n";
    const Ledger ledger = done_rows.empty() ? Ledger{} : read_ledger(sh.files.sums(id));
    std::string sums_text;  // the ledger as committed so far
    AdaptivePlan plan(p, o.seed, o.participants[index]);
    std::size_t k = 0;
    for (; !plan.done(); ++k) {
        const PlannedTrial t = plan.next();
        const Condition& c = p.conditions[static_cast<std::size_t>(t.condition)];
        std::vector<std::string> row;
        std::string line, trace_sha;  // the row as written, and its trace's SHA-256 ("-": none)
        if (k < done_rows.size()) {
            // Done before the run was interrupted: replay its answer (the next stimulus depends on it).
            row = done_rows[k];
            if (row[condition_col] != c.name || row[trial_col] != std::to_string(t.trial) || row[stimulus_col] != stimulus_label(p, t.stimulus))
                throw ExperimentError(part + ": row " + std::to_string(k + 1) + " is " + row[condition_col] + " trial " + row[trial_col] +
                                      " at " + row[stimulus_col] + ", the procedure has " + c.name + " trial " + std::to_string(t.trial) +
                                      " at " + stimulus_label(p, t.stimulus) + " there (the file is not this run's); give --overwrite to start again");
            line = csv_line(row);
            verify_done_row(p, o, sh.files, id, k, row, line, t, c, ledger);
            trace_sha = ledger.rows[k].second;
            const bool valid = row[valid_col] == "1";
            plan.record(valid, row[correct_col] == "1");
            out.invalid += !valid;
            ++out.resumed;
        } else {
            const TrialOutcome r = perform(p, o, t);
            TrialRecord rec = record_of(p, o, id, t, r);
            const AdaptivePlan::Recorded a = plan.record(r.valid, r.correct);
            rec.reversal = a.reversal;
            rec.estimate = a.estimate;
            row = results_row(p, rec);
            line = csv_line(row);
            trace_sha = commit_trace(o, sh.files, id, c, t, r);
            out.invalid += !r.valid;
        }
        out.warmup += t.warmup;
        sums_text += sha256_hex(line) + " " + trace_sha + "\n";
        part_text += line + "\n";
        {
            std::lock_guard<std::mutex> g(sh.lock);
            out.lines.push_back(line);
        }
        if (k >= done_rows.size()) {
            const StageTimer timer(&TrialProfile::files);
            write_file_atomically(sh.files.sums(id), sums_text);  // the checksums first: a row on disk has its own
            write_file_atomically(part, part_text);  // on disk before the next trial
        }
        if (o.progress) o.progress(++sh.done, std::max(sh.total, sh.done.load()));
    }
    if (k < done_rows.size())
        throw ExperimentError(part + ": " + std::to_string(done_rows.size()) + " rows, the procedure ended after " + std::to_string(k) +
                              " (the file is not this run's); give --overwrite to start again");
    const StageTimer timer(&TrialProfile::files);
    std::lock_guard<std::mutex> g(sh.lock);
    out.finished = true;
    sh.write_results(false);
}

void run_participant(Shared& sh, std::size_t index, const std::vector<std::vector<std::string>>& done_rows) {
    const Protocol& p = sh.p;
    const RunOptions& o = sh.o;
    if (p.procedure.type != ProcedureType::constant) return run_adaptive_participant(sh, index, done_rows);
    ParticipantRun& out = sh.runs[index];
    const std::string id = participant_id(o, o.participants[index]);
    const std::string part = sh.files.part(id);
    const std::vector<std::string>& columns = results_columns(p);
    auto column = [&](const char* name) { return column_index(columns, name); };
    const std::size_t condition_col = column("condition"), trial_col = column("trial"), valid_col = column("valid");
    std::string part_text = csv_line(columns) + "\n";
    const Ledger ledger = done_rows.empty() ? Ledger{} : read_ledger(sh.files.sums(id));
    std::string sums_text;  // the ledger as committed so far
    std::size_t k = 0;  // this participant's trials so far, in order
    for (std::vector<PlannedTrial> block : plan_trials(p, o.seed, o.participants[index])) {
        const std::size_t planned = block.size();
        for (std::size_t i = 0; i < block.size(); ++i, ++k) {
            PlannedTrial t = block[i];
            const Condition& c = p.conditions[static_cast<std::size_t>(t.condition)];
            std::vector<std::string> row;
            std::string line, trace_sha;  // the row as written, and its trace's SHA-256 ("-": none)
            bool valid = true;
            if (k < done_rows.size()) {
                // Done before the run was interrupted: the row must be the trial the plan puts here.
                row = done_rows[k];
                if (row[condition_col] != c.name || row[trial_col] != std::to_string(t.trial))
                    throw ExperimentError(part + ": row " + std::to_string(k + 1) + " is " + row[condition_col] + " trial " +
                                          row[trial_col] + ", the plan has " + c.name + " trial " + std::to_string(t.trial) +
                                          " there (the file is not this run's); give --overwrite to start again");
                line = csv_line(row);
                verify_done_row(p, o, sh.files, id, k, row, line, t, c, ledger);
                trace_sha = ledger.rows[k].second;
                valid = row[valid_col] == "1";
                ++out.resumed;
            } else {
                const TrialOutcome r = perform(p, o, t);
                valid = r.valid;
                row = results_row(p, record_of(p, o, id, t, r));
                line = csv_line(row);
                trace_sha = commit_trace(o, sh.files, id, c, t, r);
            }
            // At most as many repeats as planned trials: a stimulus that always faults the servo
            // cannot keep the block going for ever.
            // A warm-up trial is not analysed, so it is not repeated either.
            if (!valid && !t.warmup && p.repeat_invalid && block.size() < 2 * planned) {
                PlannedTrial again = t;
                again.seed = mix64(t.seed);
                again.trial = static_cast<int>(block.size()) + 1;
                block.push_back(again);  // presented again at the end of the block
            }
            out.invalid += !valid;
            out.warmup += t.warmup;
            sums_text += sha256_hex(line) + " " + trace_sha + "\n";
            part_text += line + "\n";
            {
                std::lock_guard<std::mutex> g(sh.lock);
                out.lines.push_back(line);
            }
            // On disk before the next trial starts.
            if (k >= done_rows.size()) {
                const StageTimer timer(&TrialProfile::files);
                write_file_atomically(sh.files.sums(id), sums_text);  // the checksums first: a row on disk has its own
                write_file_atomically(part, part_text);
            }
            if (o.progress) o.progress(++sh.done, sh.total);
        }
    }
    if (k < done_rows.size())
        throw ExperimentError(part + ": " + std::to_string(done_rows.size()) + " rows, the plan has " + std::to_string(k) +
                              " (the file is not this run's); give --overwrite to start again");
    const StageTimer timer(&TrialProfile::files);
    std::lock_guard<std::mutex> g(sh.lock);
    out.finished = true;
    sh.write_results(false);
}

}  // namespace

RunSummary run_experiment(const Protocol& p, const RunOptions& o) {
    if (o.participants.empty()) throw ExperimentError("no participants");
    if (o.output.empty()) throw ExperimentError("no output file");
    RunIdentity id;
    id.protocol_path = o.protocol_path.empty() ? p.origin : o.protocol_path;
    id.protocol = &p;
    id.seed = o.seed;
    for (std::uint64_t n : o.participants) id.participants.push_back(participant_id(o, n));
    // The wearable platform's host loop is its 100 Hz serial link (haptics/wearable/rig.hpp).
    id.device = o.observer ? std::string(kObserverDevice) + " observer:" + o.observer->text : p.device;
    id.servo_rate_hz = !o.observer && p.device == "sim-wearable" ? kWearableLinkRate : kTrialRate;
    id.traces = o.traces;
    nlohmann::json meta = make_meta(id, o.command);

    // Whose files are these? Ours to resume, another run's to refuse, or (--overwrite) to clear.
    RunFiles files(o.output);
    RunSummary sum;
    const RunState state = files.claim(meta, o.overwrite);
    if (state.complete) {
        // The same run, finished before: nothing to do, nothing rewritten.
        const ResultsTable t = read_results_csv(o.output);
        sum.rows = sum.resumed = t.rows.size();
        sum.already_complete = true;
        return sum;
    }
    if (state.resuming) {
        meta = state.meta;
        note_resume(meta, o.command);
    }
    write_meta(o.output, meta);  // before any row: until finished_utc is set, the run is unfinished

    std::size_t per_participant = 0;
    if (p.procedure.type == ProcedureType::constant) {
        for (const auto& block : plan_trials(p, o.seed, 1)) per_participant += block.size();
    } else {
        // Adaptive: at most the procedure's trials and the practice per condition (a staircase
        // usually stops sooner, on its reversals).
        const int most = p.procedure.type == ProcedureType::staircase ? p.procedure.max_trials : p.procedure.trials;
        per_participant = static_cast<std::size_t>(most + p.warmup) * p.conditions.size();
    }
    Shared sh{p, o, files, std::vector<ParticipantRun>(o.participants.size()), {}, {}, 0, {}};
    sh.total = per_participant * o.participants.size();
    std::vector<std::vector<std::vector<std::string>>> done_rows(o.participants.size());
    for (std::size_t i = 0; i < o.participants.size(); ++i) done_rows[i] = files.done_rows(results_columns(p), id.participants[i]);

    std::atomic<std::size_t> next{0};
    std::mutex error_lock;
    std::string error;
    auto worker = [&] {
        TrialProfile mine;  // this thread's stages (RunOptions::profile)
        const ProfileScope scope(o.profile ? &mine : nullptr);
        StageClock clock;  // the worker's wall time, ns
        clock.start(o.profile);
        for (std::size_t i; (i = next++) < o.participants.size();) {
            try {
                run_participant(sh, i, done_rows[i]);
            } catch (const std::exception& e) {
                std::lock_guard<std::mutex> g(error_lock);
                if (error.empty()) error = e.what();
            }
        }
        if (!o.profile) return;
        double wall = 0.0;
        clock.lap(wall);
        mine.wall = wall * 1e-9;
        std::lock_guard<std::mutex> g(sh.lock);
        sh.profile += mine;
    };
    const int jobs = std::max(1, std::min<int>(o.jobs, static_cast<int>(o.participants.size())));
    std::vector<std::thread> threads;
    for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
    worker();
    for (std::thread& t : threads) t.join();
    if (!error.empty()) throw ExperimentError(error);

    sh.write_results(true);
    for (const ParticipantRun& r : sh.runs) {
        sum.rows += r.lines.size();
        sum.invalid += r.invalid;
        sum.warmup += r.warmup;
        sum.resumed += r.resumed;
    }
    sum.profile = sh.profile;
    finish_meta(meta, sum.rows);
    write_meta(o.output, meta);
    files.finish();  // the parts are in RESULTS.csv now
    return sum;
}

}  // namespace contactlab::experiments
