// test_slurm_script.cpp — the Slurm job of `contactlab experiment slurm`, as text
// (engine/experiments/runs/slurm_script.hpp): the array's ranges (the last one partial), paths
// with spaces and quotes quoted for bash, the merge submitted with afterok on the array, and the
// merge listing every part in participant order; then the command itself: its scripts, run by
// hand as Slurm would run them (a stand-in sbatch records the merge's submission), give the bytes
// of one `experiment run` of the same participants. The real Slurm runs them in
// tests/cluster/slurm_test.sh.
#include "process.hpp"

#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/runs/slurm_script.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

using namespace cli_test;
using namespace contactlab::experiments;

namespace {

SlurmJob job_of(std::uint64_t first, std::uint64_t last, std::uint64_t per_task) {
    SlurmJob j;
    j.contactlab = "/opt/contact lab/bin/contactlab";
    j.protocol = "/home/ann/study/004.json";
    j.output = "/home/ann/study/all.csv";
    j.first = first;
    j.last = last;
    j.per_task = per_task;
    j.seed = 7;
    j.traces = false;
    j.command = "contactlab experiment slurm ...";
    return j;
}

// The text between `from` and the next `to` after it.
std::string between(const std::string& text, const std::string& from, const std::string& to) {
    const std::size_t a = text.find(from);
    REQUIRE(a != std::string::npos);
    const std::size_t b = text.find(to, a + from.size());
    REQUIRE(b != std::string::npos);
    return text.substr(a + from.size(), b - a - from.size());
}

}  // namespace

TEST_CASE("slurm script: ranges of --per-task participants, the last one partial, zero-padded names") {
    const std::vector<SlurmTask> t = slurm_tasks(job_of(1, 1000, 25));
    REQUIRE(t.size() == 40);
    CHECK(t[0].first == 1);
    CHECK(t[0].last == 25);
    CHECK(t[0].part == "p0001-0025.csv");
    CHECK(t[39].part == "p0976-1000.csv");
    const std::vector<SlurmTask> p = slurm_tasks(job_of(3, 10, 3));
    REQUIRE(p.size() == 3);
    CHECK(p[2].first == 9);
    CHECK(p[2].last == 10);  // the partial last range
    CHECK(p[2].part == "p0009-0010.csv");
    CHECK(slurm_tasks(job_of(1, 10000, 5000))[1].part == "p05001-10000.csv");  // padded to the widest number
    CHECK(slurm_tasks(job_of(4, 4, 25)).size() == 1);
    CHECK_THROWS_AS(slurm_tasks(job_of(5, 4, 1)), ExperimentError);
    CHECK_THROWS_AS(slurm_tasks(job_of(1, 4, 0)), ExperimentError);
}

TEST_CASE("slurm script: the array runs one durable range per task, the merge follows with afterok and lists every part in order") {
    SlurmJob j = job_of(3, 10, 3);
    j.partition = "short";
    j.time = "1:00:00";
    j.mem = "2G";
    const SlurmScripts s = slurm_scripts(j);
    CHECK(s.array.rfind("#!/bin/bash\n", 0) == 0);
    CHECK(contains(s.array, "\n#SBATCH --array=1-3\n"));
    CHECK(contains(s.array, "\n#SBATCH --cpus-per-task=1\n"));
    CHECK(contains(s.array, "\n#SBATCH --output=\"/home/ann/study/all.slurm/logs/task-%a.out\"\n"));
    CHECK(contains(s.array, "\n#SBATCH --partition=\"short\"\n#SBATCH --time=\"1:00:00\"\n#SBATCH --mem=\"2G\"\n"));
    CHECK(between(s.array, "sbatch this file}\" in\n", "esac\n") ==
          "  1) range=3-5 part=p0003-0005.csv ;;\n"
          "  2) range=6-8 part=p0006-0008.csv ;;\n"
          "  3) range=9-10 part=p0009-0010.csv ;;\n"
          "  *) echo \"array.sbatch: no participants for array task $SLURM_ARRAY_TASK_ID (tasks 1-3)\" >&2; exit 2 ;;\n");
    CHECK(contains(s.array, "\ncontactlab='/opt/contact lab/bin/contactlab'\n"));
    CHECK(contains(s.array, "\nparts='/home/ann/study/all.slurm/parts'\n"));
    CHECK(contains(s.array, "  sbatch --parsable --dependency=\"afterok:$SLURM_ARRAY_JOB_ID\" --kill-on-invalid-dep=yes "
                            "'/home/ann/study/all.slurm/merge.sbatch'\n"));
    CHECK(contains(s.array, "\nexec \"$contactlab\" experiment run \"$protocol\" --participants \"sim:$range\" --seed 7 --jobs 1 "
                            "--no-traces -o \"$parts/$part\"\n"));
    CHECK(contains(s.merge, "\n#SBATCH --partition=\"short\"\n"));
    CHECK(between(s.merge, "set -euo pipefail\n", "\n") == "exec '/opt/contact lab/bin/contactlab' experiment merge \\");
    CHECK(between(s.merge, "experiment merge \\\n", "\n  -o") ==
          "  '/home/ann/study/all.slurm/parts/p0003-0005.csv' \\\n"
          "  '/home/ann/study/all.slurm/parts/p0006-0008.csv' \\\n"
          "  '/home/ann/study/all.slurm/parts/p0009-0010.csv' \\");
    CHECK(contains(s.merge, "\n  -o '/home/ann/study/all.csv'\n"));
    j.traces = true;
    j.overwrite = true;
    j.cpus_per_task = 4;
    const SlurmScripts t = slurm_scripts(j);
    CHECK(contains(t.array, "--seed 7 --jobs 4 -o \"$parts/$part\"\n"));
    CHECK(contains(t.merge, "-o '/home/ann/study/all.csv' --overwrite\n"));
}

TEST_CASE("slurm script: quoting: spaces and single quotes for bash, and a double quote, which #SBATCH cannot carry, is refused") {
    CHECK(shell_quote("/a b/it's") == "'/a b/it'\\''s'");
    CHECK(slurm_dir("/x y/all.csv") == "/x y/all.slurm");
    SlurmJob j = job_of(1, 2, 1);
    j.output = "/home/ann/my study/ann's.csv";
    const SlurmScripts s = slurm_scripts(j);
    CHECK(contains(s.array, "\n#SBATCH --output=\"/home/ann/my study/ann's.slurm/logs/task-%a.out\"\n"));
    CHECK(contains(s.array, "\nparts='/home/ann/my study/ann'\\''s.slurm/parts'\n"));
    CHECK(contains(s.merge, "  -o '/home/ann/my study/ann'\\''s.csv'\n"));
    j.output = "/home/ann/\"quoted\"/all.csv";
    CHECK_THROWS_WITH_AS(slurm_scripts(j), doctest::Contains("double quote"), ExperimentError);
}
