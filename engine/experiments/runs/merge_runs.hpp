// merge_runs.hpp — `contactlab experiment merge A.csv B.csv ... -o ALL.csv`: one results file from
// runs of one study split by participants (array tasks on a cluster, or runs on several machines).
//
// The sources must be finished `experiment run` results of the same protocol (sha256), program
// (version and commit), seed, device, servo rate and traces setting, with the same columns. A
// participant in two sources is taken once if its rows are the same bytes in both, and refused
// otherwise. The merged file holds the header and each participant's rows, participants in their
// numbers' order (sim1, sim2, ...), so it is the same bytes as one run of those participants; its
// meta is a run's meta (analyze, power and calibrate read it as any other) with `merged_from`:
// every source file's path, sha256, command and host. Traces are copied into ALL.csv.traces/.
// Anything else is an ExperimentError naming the file and what differs, and nothing is written.
#pragma once

#include <string>
#include <vector>

namespace contactlab::experiments {

struct MergeSummary {
    std::size_t rows = 0;
    std::vector<std::string> participants;  // in the merged file's order
    std::size_t duplicates = 0;             // participants found, the same bytes, in more than one source
    std::size_t traces = 0;                 // trace files copied
};

// Merges `sources` into `output` (and its meta and traces). `command` goes into the meta;
// `overwrite` replaces an existing output instead of refusing.
MergeSummary merge_runs(const std::vector<std::string>& sources, const std::string& output, const std::string& command,
                        bool overwrite);

}  // namespace contactlab::experiments
