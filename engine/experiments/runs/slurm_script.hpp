// slurm_script.hpp — the text of the Slurm job that runs one study split by participants on a
// cluster (`contactlab experiment slurm`): a job array, one range of participants per task, each
// task an ordinary durable `experiment run` into its own part file, and a merge job that runs
// once every task has succeeded (afterok on the array) and writes the one results file
// (merge_runs.hpp: the same bytes as one run of all the participants).
//
// Pure text from the job's description: no file is read or written here, so the text is tested
// as text (tests/experiments/test_slurm_script.cpp). Everything the job touches is named by an
// absolute path (a cluster's nodes share the filesystem, not the working directory), quoted for
// bash. Where the files go, beside the results file RESULTS.csv:
//   RESULTS.slurm/array.sbatch    the job array (submit this one: `sbatch RESULTS.slurm/array.sbatch`)
//   RESULTS.slurm/merge.sbatch    the merge, submitted by the array's first task with afterok on the array
//   RESULTS.slurm/parts/pA-B.csv  task k's results (participants A..B, zero-padded to sort in order)
//   RESULTS.slurm/logs/           each task's and the merge's output
// A task that dies is resumed by submitting the array again: each part is a durable run, so
// finished parts are left as they are and an unfinished one carries on.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct SlurmJob {
    std::string contactlab;   // absolute path of the contactlab executable the nodes run
    std::string protocol;     // absolute path of the protocol file
    std::string output;       // absolute path of the merged results file (RESULTS.csv)
    std::uint64_t first = 1, last = 1;  // participants sim:first..last
    std::uint64_t per_task = 25;        // participants per array task (the last task may take fewer)
    std::uint64_t seed = 1;
    bool traces = true;                  // per-trial traces (false: --no-traces)
    int cpus_per_task = 1;               // each task's --jobs
    bool overwrite = false;              // the merge replaces an existing RESULTS.csv
    std::string partition, time, mem;    // sbatch's own options; "" leaves them to the cluster
    std::string command;                 // the command line that wrote the job, for its header
};

// One array task's participants and its part file's name ("p0001-0025.csv").
struct SlurmTask {
    std::uint64_t first = 0, last = 0;
    std::string part;
};

// The tasks, in participant order: ranges of per_task participants, the last one partial.
// Numbers are zero-padded to the width of `last` (at least 4), so the parts sort in order.
std::vector<SlurmTask> slurm_tasks(const SlurmJob& job);

// RESULTS.csv -> RESULTS.slurm (the job's folder, beside the results file).
std::string slurm_dir(const std::string& output);

// `text` quoted for bash: in single quotes, a single quote as '\''.
std::string shell_quote(const std::string& text);

struct SlurmScripts {
    std::string array;   // RESULTS.slurm/array.sbatch
    std::string merge;   // RESULTS.slurm/merge.sbatch
};

// Both scripts' text. Throws ExperimentError for a path that a #SBATCH line cannot carry (a
// double quote or a line break) or an empty range.
SlurmScripts slurm_scripts(const SlurmJob& job);

}  // namespace contactlab::experiments
