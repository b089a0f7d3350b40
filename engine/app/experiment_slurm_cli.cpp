// experiment_slurm_cli.cpp — `contactlab experiment slurm PROTOCOL --participants sim:A-B
// [--per-task N] [--seed S] [--no-traces] [--cpus-per-task C] -o RESULTS.csv [--partition P]
// [--time T] [--mem M] [--contactlab PATH] [--overwrite] [--submit]`: a study split by
// participants over a Slurm cluster. Writes RESULTS.slurm/array.sbatch (a job array, one range of
// participants per task, each an ordinary durable `experiment run` into RESULTS.slurm/parts/) and
// RESULTS.slurm/merge.sbatch (the merge into RESULTS.csv, after every task has succeeded), then
// prints the one command that submits them (engine/experiments/runs/slurm_script.hpp), or with
// --submit runs it. ContactLab runs no scheduler of its own: Slurm does the scheduling, the
// runs' part files make a killed task resumable, and the merge checks the parts agree.
#include "engine/app/command_line.hpp"
#include "engine/app/number_options.hpp"
#include "engine/app/participant_options.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/runs/slurm_script.hpp"
#include "haptics/atomic_file.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>

extern char** environ;

namespace contactlab::app {
namespace {

namespace fs = std::filesystem;

struct SlurmArgs {
    std::string protocol, participants, output, partition, time, mem, contactlab;
    std::uint64_t per_task = 25, seed = 1;
    int cpus_per_task = 1;
    bool no_traces = false, overwrite = false, submit = false;
};

// The executable the nodes run: --contactlab, else this one (by absolute path: a cluster shares
// the filesystem, not the PATH or the working directory of whoever submits).
std::string executable(const std::string& given_path) {
    std::error_code ec;
    if (given_path.empty()) {
        const fs::path self = fs::read_symlink("/proc/self/exe", ec);
        if (ec) throw BadInput("experiment slurm: cannot tell where this contactlab is (/proc/self/exe: " + ec.message() + "): give --contactlab PATH");
        return self.string();
    }
    const fs::path p = fs::absolute(given_path);
    if (!fs::is_regular_file(p) || access(p.c_str(), X_OK) != 0)
        throw BadInput("--contactlab: " + p.string() + " is not an executable file");
    return p.lexically_normal().string();
}

// sbatch FILE, its output (the job id) passed through; sbatch's exit status, or BadInput when
// there is no sbatch to run.
int submit(const std::string& file) {
    const char* argv[] = {"sbatch", file.c_str(), nullptr};
    pid_t pid = 0;
    if (const int e = posix_spawnp(&pid, "sbatch", nullptr, nullptr, const_cast<char**>(argv), environ); e != 0)
        throw BadInput("experiment slurm --submit: cannot run sbatch (" + std::string(std::strerror(e)) +
                       "): submit from a machine with Slurm's client commands, or without --submit and run the command printed");
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 0;
    std::fprintf(stderr, "experiment slurm: sbatch %s failed (%s %d); the scripts are written, submit again when Slurm takes them\n",
                 file.c_str(), WIFEXITED(status) ? "exit status" : "signal", WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status));
    return 1;
}

int run_slurm(const SlurmArgs& a) {
    const std::vector<std::uint64_t> people = sim_participants(a.participants, "--participants");
    const experiments::SlurmJob job{.contactlab = executable(a.contactlab),
                                    .protocol = fs::absolute(a.protocol).lexically_normal().string(),
                                    .output = fs::absolute(a.output).lexically_normal().string(),
                                    .first = people.front(),
                                    .last = people.back(),
                                    .per_task = a.per_task,
                                    .seed = a.seed,
                                    .traces = !a.no_traces,
                                    .cpus_per_task = a.cpus_per_task,
                                    .overwrite = a.overwrite,
                                    .partition = a.partition,
                                    .time = a.time,
                                    .mem = a.mem,
                                    .command = command_line()};
    if (fs::exists(job.output) && !a.overwrite)
        throw BadInput("experiment slurm: " + job.output + " exists: the merge would refuse to replace it (--overwrite lets it)");
    const fs::path dir(experiments::slurm_dir(job.output));
    std::size_t tasks = 0;
    try {
        experiments::load_protocol(job.protocol);  // a protocol that cannot run fails here, not on the cluster
        const experiments::SlurmScripts s = experiments::slurm_scripts(job);
        tasks = experiments::slurm_tasks(job).size();
        fs::create_directories(dir / "parts");
        fs::create_directories(dir / "logs");  // Slurm does not create the folder of --output
        write_file_atomically((dir / "array.sbatch").string(), s.array);
        write_file_atomically((dir / "merge.sbatch").string(), s.merge);
    } catch (const experiments::ExperimentError& e) {
        throw BadInput(e.what());
    }
    const std::string array_file = (dir / "array.sbatch").string();
    std::fprintf(stderr,
                 "experiment slurm: participants sim:%llu-%llu in %zu array task(s) of at most %llu, parts in %s, merged into %s by %s "
                 "after every task has succeeded\n",
                 static_cast<unsigned long long>(job.first), static_cast<unsigned long long>(job.last), tasks,
                 static_cast<unsigned long long>(job.per_task), (dir / "parts").c_str(), job.output.c_str(), (dir / "merge.sbatch").c_str());
    if (a.submit) return submit(array_file);
    std::printf("sbatch %s\n", experiments::shell_quote(array_file).c_str());
    return 0;
}

}  // namespace

void register_experiment_slurm_command(CLI::App& app, int& rc) {
    CLI::App* exp = app.get_subcommand("experiment");
    auto args = std::make_shared<SlurmArgs>();
    CLI::App* c = exp->add_subcommand("slurm", "Write a Slurm job array running a protocol's participants in ranges, then merging them");
    c->add_option("protocol", args->protocol, "Protocol file (JSON, scenes/README.md)")->required();
    c->add_option("--participants", args->participants, "sim:A-B: the simulated participants A..B, split into ranges")->required();
    add_whole_option(c, "--per-task", args->per_task, 1, kMaxParticipant, "Participants per array task (the last may take fewer)");
    add_whole_option(c, "--seed", args->seed, 0, kMaxSeed, "Seed of the trial orders and the perceptual noise (as experiment run)");
    c->add_flag("--no-traces", args->no_traces, "Skip the per-trial traces");
    add_whole_option(c, "--cpus-per-task", args->cpus_per_task, 1, kMaxJobs, "CPUs each task asks for and runs participants on (--jobs)");
    c->add_option("-o,--output", args->output, "The merged results CSV; the job's scripts, parts and logs go beside it in STEM.slurm/")
        ->required();
    c->add_option("--partition", args->partition, "sbatch --partition (default: the cluster's)");
    c->add_option("--time", args->time, "sbatch --time, each task's and the merge's limit (e.g. 2:00:00)");
    c->add_option("--mem", args->mem, "sbatch --mem, each task's and the merge's memory (e.g. 2G)");
    c->add_option("--contactlab", args->contactlab, "The contactlab the nodes run (default: this one, by absolute path)");
    c->add_flag("--overwrite", args->overwrite, "Let the merge replace an existing output");
    c->add_flag("--submit", args->submit, "Submit the array with sbatch instead of printing the command");
    c->callback([args, &rc] {
        args->protocol = installed_data_path(args->protocol);
        rc = run_slurm(*args);
    });
}

}  // namespace contactlab::app
