// run_meta.hpp — a results file's provenance, RESULTS.csv.meta.json beside it (scenes/README.md,
// "Experiments: provenance"): what made it (program version and commit, the command line), from
// what (the protocol's path, bytes' SHA-256 and content, the seed, the participants, the device
// and its servo rate) and when (started, finished: null while the run is unfinished). The same
// keys identify a run, so a run started again into the same file resumes only that run and
// refuses any other.
#pragma once

#include "engine/experiments/protocol/protocol.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace contactlab::experiments {

inline constexpr const char* kMetaFormat = "contactlab results meta";

// RESULTS.csv -> RESULTS.csv.meta.json
std::string meta_path(const std::string& results_path);

// Now, as ISO 8601 UTC to the second ("2025-01-31T12:00:00Z").
std::string utc_now();

// This machine's host name (gethostname), "" when it has none: where a run ran, for the meta.
std::string host_name();

struct RunIdentity {
    std::string protocol_path;
    const Protocol* protocol = nullptr;
    std::uint64_t seed = 1;
    std::vector<std::string> participants;  // as the participant column writes them
    std::string device;                     // the device's name ("sim-cld")
    double servo_rate_hz = 1000.0;
    bool traces = true;                     // per-trial traces in RESULTS.csv.traces/
};

// A new run's meta: finished_utc null until finish_meta.
nlohmann::json make_meta(const RunIdentity& id, const std::string& command);
void finish_meta(nlohmann::json& meta, std::size_t rows);
// A resumed run adds when and how it was started again.
void note_resume(nlohmann::json& meta, const std::string& command);

// The meta beside a results file, or nullopt when there is none; ExperimentError naming the file
// when it is not a meta file this program reads.
std::optional<nlohmann::json> read_meta(const std::string& results_path);

// "" when `old_meta` was made by a run with the same identity as `now`, else what differs, in
// words ("another protocol (sha256 1f2e... here, 9a8b... in the file)").
std::string identity_difference(const nlohmann::json& old_meta, const nlohmann::json& now);

// Writes the meta atomically.
void write_meta(const std::string& results_path, const nlohmann::json& meta);

}  // namespace contactlab::experiments
