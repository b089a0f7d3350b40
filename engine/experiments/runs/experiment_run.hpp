// experiment_run.hpp — `contactlab experiment run`: a protocol's trials for one or more
// participants, in the order trial_plan.hpp gives, performed by the simulated participant
// (sim_participant.hpp), into one results CSV (one row per trial; columns in scenes/README.md)
// with its provenance beside it (RESULTS.csv.meta.json, run_meta.hpp) and per-trial traces in
// RESULTS.csv.traces/. An invalid trial (the servo faulted) is presented again at the end of its
// block when the protocol says so, so every block ends with its planned number of valid trials.
//
// Durable and resumable: each participant's finished trials are kept in RESULTS.csv.parts/ID.csv,
// rewritten atomically after every trial (the trace first, then the row), so a killed run loses
// at most the trial in progress. RESULTS.csv is rewritten from the parts whenever a participant
// finishes and at the end, when the meta gets its finished_utc and the parts are removed. The
// same command started again resumes where the parts end and writes the same bytes an
// uninterrupted run writes. A run into files made by another run (another protocol, seed,
// participant set, device, rate, traces setting or build), or by something without a meta file,
// is refused unless `overwrite`, which clears them and their traces first.
//
// Adaptive procedures (staircase, QUEST+; adaptive_plan.hpp) choose each stimulus from the
// answers so far: the participant's trials come from an AdaptivePlan, and a resumed run replays
// the stored answers through it, checking each stored row is the trial the plan puts there.
//
// Participants run in parallel on `jobs` threads; the file does not depend on `jobs` (rows are
// written in participant order).
//
// Room engine/experiments/runs/: `experiment run` (here), its durable part files and meta, results rows, the
// editor's live sessions. Includes participants/, procedures/, protocol/ and base/.
// The rooms and their arrows: docs/ARCHITECTURE.md, "The experiments' rooms".
#pragma once

#include "engine/experiments/participants/model_observer.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/runs/results_row.hpp"
#include "engine/experiments/base/trial_profile.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct RunOptions {
    std::vector<std::uint64_t> participants;  // simulated participants' numbers (1, 2, ...)
    // Model observers (model_observer.hpp) instead of the simulated participant: no servo, no
    // traces; the participants are "obs1", "obs2", ... and the meta's device names the observer.
    std::optional<ObserverSpec> observer;
    std::uint64_t seed = 1;
    std::string output;                       // RESULTS.csv
    std::string protocol_path;                // for the meta (the Protocol's origin when empty)
    std::string command;                      // the command line, for the meta
    bool traces = true;                       // RESULTS.csv.traces/P-CONDITION-TRIAL.csv at 100 Hz
    bool overwrite = false;                   // replace another run's files instead of refusing
    int jobs = 1;
    // Time each stage of the trials (trial_profile.hpp) into RunSummary::profile; the rows and
    // traces do not change.
    bool profile = false;
    std::function<void(std::size_t done, std::size_t total)> progress;  // trials, any thread
};

struct RunSummary {
    std::size_t rows = 0, invalid = 0, warmup = 0;
    std::size_t resumed = 0;        // rows found on disk from an earlier, interrupted start
    bool already_complete = false;  // the file held the whole run: nothing was run
    TrialProfile profile;           // RunOptions::profile: the trials run now, by stage
};

// Throws ExperimentError for options it cannot honour and files it must not touch.
RunSummary run_experiment(const Protocol& p, const RunOptions& o);

}  // namespace contactlab::experiments
