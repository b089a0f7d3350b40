// experiment_merge_cli.cpp — `contactlab experiment merge A.csv B.csv ... -o ALL.csv [--overwrite]`:
// one results file from runs of one study split by participants
// (engine/experiments/runs/merge_runs.hpp). A bad merge (another protocol, seed, build, device or
// rate; a participant run twice with other rows; an unfinished or truncated source) exits 2,
// naming the file and what differs.
#include "engine/app/command_line.hpp"
#include "engine/app/subcommands.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/runs/merge_runs.hpp"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace contactlab::app {
namespace {

struct MergeArgs {
    std::vector<std::string> sources;
    std::string output;
    bool overwrite = false;
};

int run_merge(const MergeArgs& a) {
    try {
        const experiments::MergeSummary s = experiments::merge_runs(a.sources, a.output, command_line(), a.overwrite);
        std::printf("experiment merge: %zu results files, %zu participants, %zu rows", a.sources.size(), s.participants.size(),
                    s.rows);
        if (s.duplicates) std::printf(" (%zu participant(s) in more than one file, the same rows: taken once)", s.duplicates);
        if (s.traces) std::printf(", %zu trace files", s.traces);
        std::printf("; written to %s with %s.meta.json\n", a.output.c_str(), a.output.c_str());
    } catch (const experiments::ExperimentError& e) {
        throw BadInput(e.what());
    }
    return 0;
}

}  // namespace

void register_experiment_merge_command(CLI::App& app, int& rc) {
    CLI::App* exp = app.get_subcommand("experiment");
    auto args = std::make_shared<MergeArgs>();
    CLI::App* c = exp->add_subcommand("merge", "One results file from runs of one study split by participants (e.g. cluster tasks)");
    c->add_option("results", args->sources, "Results CSVs of finished runs (each with its .meta.json)")->required();
    c->add_option("-o,--output", args->output, "The merged results CSV (with its meta and traces)")->required();
    c->add_flag("--overwrite", args->overwrite, "Replace an existing output");
    c->callback([&rc, args] { rc = run_merge(*args); });
}

}  // namespace contactlab::app
