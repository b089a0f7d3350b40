// pooling.hpp — `experiment analyze A.csv B.csv ...`: several results files read as one table,
// each with its provenance (FILE.meta.json, run_meta.hpp; null when there is none). Files from
// different protocols (different protocol_sha256) are refused unless `pool_protocols`: their
// trials are not the same experiment, so pooling them changes what is tested. What cannot be
// checked is said in warnings: a file without a meta, an unfinished run, a participant id found
// in more than one file (pooled as one person).
#pragma once

#include "engine/experiments/base/results_table.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace contactlab::experiments {

struct PooledResults {
    ResultsTable table;               // the rows of every file, in file order, columns of the first
    nlohmann::json provenance;        // { FILE: its meta object, or null }
    std::vector<std::string> warnings;
};

// Throws ExperimentError naming the file: unreadable, other columns, another protocol.
PooledResults pool_results(const std::vector<std::string>& paths, bool pool_protocols);

}  // namespace contactlab::experiments
