// slurm_script.cpp — the Slurm job array and merge job of `contactlab experiment slurm`, as text
// (slurm_script.hpp).
#include "engine/experiments/runs/slurm_script.hpp"

#include "engine/experiments/base/results_table.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace contactlab::experiments {
namespace {

namespace fs = std::filesystem;

std::string padded(std::uint64_t n, std::size_t width) {
    std::string s = std::to_string(n);
    return std::string(width > s.size() ? width - s.size() : 0, '0') + s;
}

// A #SBATCH line takes a value in double quotes (sbatch reads them as the shell would, without
// escapes), so a path holding one, or a line break, cannot be written there.
std::string directive_value(const std::string& path, const char* what) {
    if (path.find_first_of("\"\n\r") != std::string::npos)
        throw ExperimentError("experiment slurm: " + std::string(what) + " \"" + path +
                              "\" holds a double quote or a line break, which an #SBATCH line cannot carry: choose another path");
    return "\"" + path + "\"";
}

// sbatch's own options, the same for the array and the merge.
void resources(std::ostringstream& s, const SlurmJob& job) {
    if (!job.partition.empty()) s << "#SBATCH --partition=" << directive_value(job.partition, "--partition") << "\n";
    if (!job.time.empty()) s << "#SBATCH --time=" << directive_value(job.time, "--time") << "\n";
    if (!job.mem.empty()) s << "#SBATCH --mem=" << directive_value(job.mem, "--mem") << "\n";
}

}  // namespace

std::vector<SlurmTask> slurm_tasks(const SlurmJob& job) {
    if (job.first < 1 || job.last < job.first || job.per_task < 1)
        throw ExperimentError("experiment slurm: participants " + std::to_string(job.first) + "-" + std::to_string(job.last) + " in tasks of " +
                              std::to_string(job.per_task) + ": need 1 <= first <= last and at least 1 per task");
    const std::size_t width = std::max<std::size_t>(4, std::to_string(job.last).size());
    std::vector<SlurmTask> tasks;
    for (std::uint64_t a = job.first; a <= job.last; a += job.per_task) {
        const std::uint64_t b = std::min(job.last, a + job.per_task - 1);
        tasks.push_back({a, b, "p" + padded(a, width) + "-" + padded(b, width) + ".csv"});
        if (b == job.last) break;  // a + per_task could wrap past the largest number
    }
    return tasks;
}

std::string slurm_dir(const std::string& output) {
    const fs::path out(output);
    return (out.parent_path() / (out.stem().string() + ".slurm")).string();
}

std::string shell_quote(const std::string& text) {
    std::string out = "'";
    for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

SlurmScripts slurm_scripts(const SlurmJob& job) {
    const std::vector<SlurmTask> tasks = slurm_tasks(job);
    const fs::path dir(slurm_dir(job.output));
    const std::string array_file = (dir / "array.sbatch").string(), merge_file = (dir / "merge.sbatch").string();
    const std::string parts = (dir / "parts").string(), logs = (dir / "logs").string();
    const std::string range = "sim:" + std::to_string(job.first) + "-" + std::to_string(job.last);

    std::ostringstream a;
    a << "#!/bin/bash\n"
      << "# Participants " << range << " of " << job.protocol << ", " << job.per_task << " per task, as a Slurm job array of "
      << tasks.size() << " tasks; each task is an ordinary durable `experiment run` into its own part file in\n"
      << "# " << parts << ", and the merge job (merge.sbatch) makes them " << job.output << " once every task has succeeded.\n"
      << "# Written by: " << job.command << "\n"
      << "# Submit: sbatch " << shell_quote(array_file) << "\n"
      << "# A task that failed or was killed: submit the array again (all of it, or the failed tasks with\n"
      << "# --array=K,...): finished parts are kept as they are, an unfinished one resumes.\n"
      << "#SBATCH --job-name=contactlab-run\n"
      << "#SBATCH --array=1-" << tasks.size() << "\n"
      << "#SBATCH --cpus-per-task=" << job.cpus_per_task << "\n"
      << "#SBATCH --output=" << directive_value(logs + "/task-%a.out", "the results file's folder") << "\n";
    resources(a, job);
    a << "set -euo pipefail\n"
      << "contactlab=" << shell_quote(job.contactlab) << "\n"
      << "protocol=" << shell_quote(job.protocol) << "\n"
      << "parts=" << shell_quote(parts) << "\n"
      << "case \"${SLURM_ARRAY_TASK_ID:?runs as a task of a Slurm job array: sbatch this file}\" in\n";
    for (std::size_t k = 0; k < tasks.size(); ++k)
        a << "  " << k + 1 << ") range=" << tasks[k].first << "-" << tasks[k].last << " part=" << tasks[k].part << " ;;\n";
    a << "  *) echo \"array.sbatch: no participants for array task $SLURM_ARRAY_TASK_ID (tasks 1-" << tasks.size()
      << ")\" >&2; exit 2 ;;\n"
      << "esac\n"
      << "# The lowest task of this submission submits the merge, to start once every task of the array has\n"
      << "# succeeded (afterok); if one fails, Slurm cancels that merge (--kill-on-invalid-dep) and the next\n"
      << "# submission of the array submits another.\n"
      << "if [ \"$SLURM_ARRAY_TASK_ID\" = \"${SLURM_ARRAY_TASK_MIN:-1}\" ]; then\n"
      << "  sbatch --parsable --dependency=\"afterok:$SLURM_ARRAY_JOB_ID\" --kill-on-invalid-dep=yes " << shell_quote(merge_file) << "\n"
      << "fi\n"
      << "exec \"$contactlab\" experiment run \"$protocol\" --participants \"sim:$range\" --seed " << job.seed << " --jobs "
      << job.cpus_per_task << (job.traces ? "" : " --no-traces") << " -o \"$parts/$part\"\n";

    std::ostringstream m;
    m << "#!/bin/bash\n"
      << "# The merge of " << array_file << "'s parts into " << job.output << " (participants " << range << ", in their order);\n"
      << "# submitted by the array's lowest task, to run once every task has succeeded.\n"
      << "# Written by: " << job.command << "\n"
      << "#SBATCH --job-name=contactlab-merge\n"
      << "#SBATCH --output=" << directive_value(logs + "/merge.out", "the results file's folder") << "\n";
    resources(m, job);
    m << "set -euo pipefail\n"
      << "exec " << shell_quote(job.contactlab) << " experiment merge \\\n";
    for (const SlurmTask& t : tasks) m << "  " << shell_quote(parts + "/" + t.part) << " \\\n";
    m << "  -o " << shell_quote(job.output) << (job.overwrite ? " --overwrite" : "") << "\n";
    return {a.str(), m.str()};
}

}  // namespace contactlab::experiments
