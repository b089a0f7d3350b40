// finished_run.hpp — a finished `experiment run` results file, read and checked as a whole: its
// meta (which run made it), finished, its rows as many as the meta says, and its bytes exactly as
// the run wrote them. What the merge (merge_runs.hpp) takes as a source and `experiment power` /
// `experiment calibrate` take as a pool (--pool-from): a file that fails any check is an
// ExperimentError naming the file and why, so no figure is drawn from a truncated, edited or
// unfinished run, or from another protocol's.
#pragma once

#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/protocol/protocol.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct FinishedRun {
    std::string path;
    std::string bytes;  // the CSV as on disk
    nlohmann::json meta;
    ResultsTable table;
    // Each participant's rows, as the lines the run wrote, in file order.
    std::map<std::string, std::vector<std::string>> rows_of;
    std::vector<std::string> participants;  // in file order (a run's and a merge's: by their numbers)
};

FinishedRun read_finished_run(const std::string& path);

// A finished run taken as a pool of participants for `protocol`: the meta's protocol_sha256 is
// the protocol's, and it holds at least `needed` participants. `option` names the option that
// gave the file, for messages ("--pool-from").
FinishedRun read_pool_run(const std::string& path, const Protocol& protocol, std::size_t needed, const std::string& option);

// The run's table with the rows of its first `n` participants (file order) only.
ResultsTable first_participants(const FinishedRun& run, std::size_t n);

}  // namespace contactlab::experiments
