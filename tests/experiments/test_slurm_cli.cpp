// test_slurm_cli.cpp — `contactlab experiment slurm`: the scripts it writes beside -o (in a folder
// whose path holds a space), the one sbatch command it prints, and, run task by task as Slurm
// would run them (bash, the array's environment, a stand-in sbatch that records the merge's
// submission), the merged file is the same bytes as one `experiment run` of the same participants.
// Bad input exits 2 naming what. The real Slurm runs the same scripts in tests/cluster/slurm_test.sh.
#include "process.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

using namespace cli_test;

namespace {

const std::string kProtocol = "scenes/experiments/004-surface-orientation.json";  // seed 004: ~1 s a participant

std::string protocol_path() { return (source_dir() / kProtocol).string(); }

// Runs `bash SCRIPT` with the environment Slurm gives an array task (task id, the array's lowest
// task and job id), and `bin` first on the PATH.
ProcessResult run_task(const std::string& script, const std::string& task, const std::string& bin) {
    const char* path = std::getenv("PATH");
    return run_process("/usr/bin/env", {"SLURM_ARRAY_TASK_ID=" + task, "SLURM_ARRAY_TASK_MIN=1", "SLURM_ARRAY_JOB_ID=4242",
                                        "PATH=" + bin + ":" + (path ? path : "/usr/bin:/bin"), "bash", script},
                       {}, std::chrono::seconds(120));
}

}  // namespace

TEST_CASE("experiment slurm: the array's tasks and the merge, run as Slurm runs them, give the bytes of one run") {
    TempDir dir;
    const fs::path study = dir.path() / "my study";
    fs::create_directories(study);
    const std::string out = (study / "all.csv").string();
    const ProcessResult g = run_contactlab({"experiment", "slurm", protocol_path(), "--participants", "sim:1-3", "--per-task", "2",
                                            "--seed", "1", "--no-traces", "-o", out, "--time", "0:10:00"});
    INFO(g.err);
    REQUIRE(g.exit_code == 0);
    const fs::path slurm = study / "all.slurm";
    CHECK(g.out == "sbatch '" + (slurm / "array.sbatch").string() + "'\n");
    CHECK(contains(g.err, "2 array task(s) of at most 2"));
    CHECK(fs::is_directory(slurm / "logs"));
    const std::string array = read_text((slurm / "array.sbatch").string());
    CHECK(contains(array, "\ncontactlab='" + fs::canonical(exe_path()).string() + "'\n"));  // by absolute path
    CHECK(contains(array, "\n#SBATCH --time=\"0:10:00\"\n"));

    // A stand-in sbatch: records what it was asked to submit.
    const fs::path bin = dir.path() / "bin";
    fs::create_directories(bin);
    write_text((bin / "sbatch").string(), "#!/bin/bash\nprintf '%s\\n' \"$*\" >> \"" + dir.file("submitted") + "\"\necho 4243\n");
    fs::permissions(bin / "sbatch", fs::perms::owner_all);
    for (const std::string task : {"2", "1"}) {  // tasks start in any order
        const ProcessResult t = run_task((slurm / "array.sbatch").string(), task, bin.string());
        INFO(t.err);
        REQUIRE(t.exit_code == 0);
    }
    // Only the lowest task submitted the merge, after the whole array succeeds.
    CHECK(read_text(dir.file("submitted")) ==
          "--parsable --dependency=afterok:4242 --kill-on-invalid-dep=yes " + (slurm / "merge.sbatch").string() + "\n");
    CHECK(fs::exists(slurm / "parts" / "p0001-0002.csv"));
    CHECK(fs::exists(slurm / "parts" / "p0003-0003.csv"));
    const ProcessResult m = run_process("/bin/bash", {(slurm / "merge.sbatch").string()}, {}, std::chrono::seconds(60));
    INFO(m.err);
    REQUIRE(m.exit_code == 0);
    const ProcessResult one = run_contactlab({"experiment", "run", protocol_path(), "--participants", "sim:1-3", "--seed", "1",
                                              "--no-traces", "-o", dir.file("one.csv")});
    REQUIRE(one.exit_code == 0);
    CHECK(read_text(out) == read_text(dir.file("one.csv")));
    // An array task Slurm should not have run says so.
    const ProcessResult bad = run_task((slurm / "array.sbatch").string(), "3", bin.string());
    CHECK(bad.exit_code == 2);
    CHECK(contains(bad.err, "no participants for array task 3 (tasks 1-2)"));
}

TEST_CASE("experiment slurm: bad input exits 2 naming what") {
    TempDir dir;
    auto refused = [&](const std::vector<std::string>& args, const std::string& says) {
        const ProcessResult r = run_contactlab(args);
        CAPTURE(r.err);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, says));
    };
    const std::string out = dir.file("all.csv");
    refused({"experiment", "slurm", protocol_path(), "--participants", "sim:5-2", "-o", out}, "--participants: expected sim:N or sim:A-B");
    refused({"experiment", "slurm", protocol_path(), "--participants", "sim:1-4", "--per-task", "0", "-o", out}, "--per-task");
    refused({"experiment", "slurm", dir.file("none.json"), "--participants", "sim:1-4", "-o", out}, "none.json");
    refused({"experiment", "slurm", protocol_path(), "--participants", "sim:1-4", "--contactlab", dir.file("nothing"), "-o", out},
            "--contactlab: " + dir.file("nothing") + " is not an executable file");
    write_text(out, "x\n");
    refused({"experiment", "slurm", protocol_path(), "--participants", "sim:1-4", "-o", out}, out + " exists");
    CHECK_FALSE(fs::exists(dir.file("all.slurm")));
}
