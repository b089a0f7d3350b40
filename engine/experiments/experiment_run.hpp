// experiment_run.hpp — `contactlab experiment run`: a protocol's trials for one or more
// participants, in the order trial_plan.hpp gives, performed by the simulated participant
// (sim_participant.hpp), into one results CSV (one row per trial; columns in scenes/README.md)
// and per-trial traces in RESULTS.traces/ beside it. An invalid trial (the servo faulted) is
// presented again at the end of its block when the protocol says so, so every block ends with
// its planned number of valid trials. Participants run in parallel on `jobs` threads; the file
// does not depend on `jobs` (rows are written in participant order).
#pragma once

#include "engine/experiments/protocol.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct RunOptions {
    std::vector<std::uint64_t> participants;  // simulated participants' numbers (1, 2, ...)
    std::uint64_t seed = 1;
    std::string output;                       // RESULTS.csv
    bool traces = true;                       // RESULTS.traces/P-CONDITION-TRIAL.csv at 100 Hz
    int jobs = 1;
    std::function<void(std::size_t done, std::size_t total)> progress;  // trials, any thread
};

struct RunSummary {
    std::size_t rows = 0, invalid = 0, warmup = 0;
};

// The results file's columns, in order.
const std::vector<std::string>& results_columns(const Protocol& p);

// Throws ExperimentError for options it cannot honour.
RunSummary run_experiment(const Protocol& p, const RunOptions& o);

}  // namespace contactlab::experiments
