// test_checked_numbers.cpp — issue 49, "Every number checked", on the command line: the real
// `contactlab` refuses every number it cannot take as given, with exit 2 and a message naming the
// option, the value as given (shortened when long) and the range. CLI11's own conversion wrapped
// `--seed -1` to 18446744073709551615 and saturated 18446744073709551616 and longer to the same;
// `--participants sim:-3` became participant 18446744073709551613. One named case per input.
#include "process.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

using namespace cli_test;

namespace {

const char* kSeedRange = "expected a whole number from 0 to 18446744073709551615";
const char* kJobsRange = "expected a whole number from 0 to 1024";

std::string protocol() { return (source_dir() / "scenes/experiments/003-curvature-cld.json").string(); }

// `experiment run` with one option changed; it must be refused before anything is written.
ProcessResult run_with(const TempDir& dir, const std::vector<std::string>& extra, const char* who = "sim") {
    std::vector<std::string> a = {"experiment", "run", protocol(), "--participant", who, "--no-traces", "-o", dir.file("r.csv")};
    a.insert(a.end(), extra.begin(), extra.end());
    return run_contactlab(a);
}

// Refused with exit 2, saying `what`, and nothing written.
void check_refused(const TempDir& dir, const ProcessResult& p, const std::string& what) {
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, what));
    CHECK(dir.entries().empty());
}

}  // namespace

TEST_CASE("issue 49: experiment run --seed -1 is refused, not wrapped to 18446744073709551615") {
    TempDir dir;
    check_refused(dir, run_with(dir, {"--seed", "-1"}), std::string("--seed: ") + kSeedRange + ", got \"-1\"");
}

TEST_CASE("issue 49: experiment run --seed 18446744073709551616 (2^64) is refused, not saturated") {
    TempDir dir;
    check_refused(dir, run_with(dir, {"--seed", "18446744073709551616"}),
                  std::string("--seed: ") + kSeedRange + ", got \"18446744073709551616\"");
}

TEST_CASE("issue 49: experiment run --seed 99999999999999999999999 is refused, not saturated") {
    TempDir dir;
    check_refused(dir, run_with(dir, {"--seed", "99999999999999999999999"}),
                  std::string("--seed: ") + kSeedRange + ", got \"99999999999999999999999\"");
}

TEST_CASE("issue 49: experiment run --seed with an empty value is refused") {
    TempDir dir;
    check_refused(dir, run_with(dir, {"--seed", ""}), std::string("--seed: ") + kSeedRange + ", got \"\"");
}

TEST_CASE("issue 49: experiment run --seed 010, +1, 0x10 and 1e3 are refused (CLI11 read 010 as octal 8)") {
    TempDir dir;
    check_refused(dir, run_with(dir, {"--seed", "010"}),
                  std::string("--seed: ") + kSeedRange + " (decimal digits, without a sign or a leading zero), got \"010\"");
    check_refused(dir, run_with(dir, {"--seed", "+1"}), "(decimal digits, without a sign or a leading zero), got \"+1\"");
    check_refused(dir, run_with(dir, {"--seed", "0x10"}), std::string("--seed: ") + kSeedRange + ", got \"0x10\"");
    check_refused(dir, run_with(dir, {"--seed", "1e3"}), std::string("--seed: ") + kSeedRange + ", got \"1e3\"");
    check_refused(dir, run_with(dir, {"--seed", " 1"}), std::string("--seed: ") + kSeedRange + ", got \" 1\"");
}

TEST_CASE("issue 49: experiment run --seed of 100,000 digits is refused with the value shortened") {
    TempDir dir;
    const std::string huge = "1" + std::string(99998, '0') + "7";
    const auto p = run_with(dir, {"--seed", huge});
    check_refused(dir, p, std::string("--seed: ") + kSeedRange + ", got \"" + huge.substr(0, 28) + "...\" (100000 characters, shortened");
    CHECK(contains(p.err, "ends \"..." + huge.substr(huge.size() - 28) + "\""));
    CHECK(p.err.size() < 400);
}

TEST_CASE("issue 49: experiment run --jobs -1 is refused") {
    TempDir dir;
    check_refused(dir, run_with(dir, {"--jobs", "-1"}), std::string("--jobs: ") + kJobsRange + ", got \"-1\"");
}

TEST_CASE("issue 49: experiment run --jobs with an empty value is refused") {
    TempDir dir;
    check_refused(dir, run_with(dir, {"--jobs", ""}), std::string("--jobs: ") + kJobsRange + ", got \"\"");
}

TEST_CASE("issue 49: experiment run --jobs 4294967297 is refused, not truncated to 1") {
    TempDir dir;
    check_refused(dir, run_with(dir, {"--jobs", "4294967297"}), std::string("--jobs: ") + kJobsRange + ", got \"4294967297\"");
}

TEST_CASE("issue 49: experiment run --participants sim:-3 is refused, not participant 18446744073709551613") {
    TempDir dir;
    check_refused(dir, run_with(dir, {}, "sim:-3"),
                  "--participant: expected sim:N or sim:A-B with whole numbers 1 <= A <= B <= 10000 (at most 10000 participants in a "
                  "run), got \"sim:-3\"");
    std::vector<std::string> a = {"experiment", "run", protocol(), "--participants", "sim:-3", "-o", dir.file("r.csv")};
    check_refused(dir, run_contactlab(a), "--participants: expected sim:N or sim:A-B with whole numbers 1 <= A <= B <= 10000");
}

TEST_CASE("issue 49: experiment run --participants sim:99999999999999999999-99999999999999999999 is refused, not saturated") {
    TempDir dir;
    check_refused(dir,
                  run_contactlab({"experiment", "run", protocol(), "--participants", "sim:99999999999999999999-99999999999999999999",
                                  "-o", dir.file("r.csv")}),
                  "--participants: expected sim:N or sim:A-B with whole numbers 1 <= A <= B <= 10000 (at most 10000 participants in a "
                  "run), got \"sim:99999999999999999999-99999999999999999999\"");
}

TEST_CASE("issue 49: experiment run --participants sim:1-999999999 is refused by the same rule, which it states") {
    TempDir dir;
    for (const char* spec : {"sim:1-999999999", "sim:10001", "sim:0", "sim:3-2", "sim:", "sim:1-2-3", "sim:01-2", "sim:1-"})
        check_refused(dir, run_contactlab({"experiment", "run", protocol(), "--participants", spec, "-o", dir.file("r.csv")}),
                      std::string("--participants: expected sim:N or sim:A-B with whole numbers 1 <= A <= B <= 10000 (at most 10000 "
                                  "participants in a run), got \"") +
                          spec + "\"");
}

TEST_CASE("issue 49: experiment run --participants observer:...:-3 is refused like sim:-3") {
    TempDir dir;
    const std::string spec = "observer:logistic:threshold=2,scale=0.4:-3";
    check_refused(dir, run_contactlab({"experiment", "run", protocol(), "--participants", spec, "-o", dir.file("r.csv")}),
                  "--participants: expected sim:N or sim:A-B with whole numbers 1 <= A <= B <= 10000 (at most 10000 participants in a "
                  "run), got \"" + spec + "\"");
}

TEST_CASE("issue 49: experiment power --seed -1, --jobs -1 and --pool 99999999999999999999 are refused") {
    TempDir dir;
    auto power = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = {"experiment", "power", protocol(), "--participants", "2-3", "--json", dir.file("p.json")};
        a.insert(a.end(), extra.begin(), extra.end());
        return run_contactlab(a);
    };
    check_refused(dir, power({"--seed", "-1"}), std::string("--seed: ") + kSeedRange + ", got \"-1\"");
    check_refused(dir, power({"--jobs", "-1"}), std::string("--jobs: ") + kJobsRange + ", got \"-1\"");
    check_refused(dir, power({"--jobs", ""}), std::string("--jobs: ") + kJobsRange + ", got \"\"");
    check_refused(dir, power({"--pool", "99999999999999999999"}), "--pool: expected a whole number from 2 to 10000, got \"99999999999999999999\"");
    check_refused(dir, power({"--resamples", "0"}), "--resamples: expected a whole number from 1 to 1000000, got \"0\"");
    check_refused(dir, power({"--alpha", "1.5"}), "--alpha: must lie in (0, 1), e.g. 0.05, got \"1.5\"");
    check_refused(dir, power({"--alpha", "nan"}), "--alpha: expected a number in (0, 1), e.g. 0.05, got \"nan\"");
}

TEST_CASE("issue 49: experiment power --participants 2-99999999999999999999 is refused, not saturated") {
    TempDir dir;
    check_refused(dir,
                  run_contactlab({"experiment", "power", protocol(), "--participants", "2-99999999999999999999", "--json", dir.file("p.json")}),
                  "--participants: group sizes A-B need whole numbers 2 <= A <= B <= 10000 (a paired t test needs 2), e.g. 4-16 or one "
                  "size N, got \"2-99999999999999999999\"");
    check_refused(dir, run_contactlab({"experiment", "power", protocol(), "--participants", "-3", "--json", dir.file("p.json")}),
                  "got \"-3\"");
}

TEST_CASE("issue 49: experiment power --conditions A,A is refused: a condition compared with itself") {
    TempDir dir;
    check_refused(dir,
                  run_contactlab({"experiment", "power", protocol(), "--participants", "2-3", "--conditions", "A,A", "--json", dir.file("p.json")}),
                  "--conditions: \"A\" compared with itself: name two different conditions A,B, got \"A,A\"");
}

TEST_CASE("issue 49: experiment power --conditions with a lone comma is refused") {
    TempDir dir;
    check_refused(dir,
                  run_contactlab({"experiment", "power", protocol(), "--participants", "2-3", "--conditions", ",", "--json", dir.file("p.json")}),
                  "--conditions: expected two conditions A,B (names without commas), got \",\"");
    check_refused(dir,
                  run_contactlab({"experiment", "power", protocol(), "--participants", "2-3", "--conditions", "", "--json", dir.file("p.json")}),
                  "--conditions: expected two conditions A,B (names without commas), got \"\"");
}

TEST_CASE("issue 49: experiment power --conditions A,B,x is refused as not two conditions (was: no condition B,x)") {
    TempDir dir;
    const auto p =
        run_contactlab({"experiment", "power", protocol(), "--participants", "2-3", "--conditions", "A,B,x", "--json", dir.file("p.json")});
    check_refused(dir, p, "--conditions: expected two conditions A,B (names without commas), got \"A,B,x\"");
    CHECK_FALSE(contains(p.err, "no condition"));
}

TEST_CASE("issue 49: experiment calibrate --seed -1, --jobs empty, --participants and --evaluations out of range are refused") {
    TempDir dir;
    write_text(dir.file("t.json"), R"({"format": "contactlab calibration targets", "version": 1, "targets": [
      {"name": "phi A", "protocol": "003-curvature-cld.json", "figure": "/conditions/A/n", "value": 1, "scale": 1, "source": "the test"}]})");
    auto calibrate = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = {"experiment", "calibrate", protocol(), "--target", dir.file("t.json"), "--param",
                                      "stiffness_noise=0.02:3", "--fit", "all", "--json", dir.file("c.json")};
        a.insert(a.end(), extra.begin(), extra.end());
        const auto p = run_contactlab(a);
        INFO("stderr: " << p.err);
        CHECK(p.exit_code == 2);
        CHECK_FALSE(std::filesystem::exists(dir.file("c.json")));
        return p.err;
    };
    CHECK(contains(calibrate({"--seed", "-1"}), std::string("--seed: ") + kSeedRange + ", got \"-1\""));
    CHECK(contains(calibrate({"--jobs", ""}), std::string("--jobs: ") + kJobsRange + ", got \"\""));
    CHECK(contains(calibrate({"--participants", "99999999999999999999"}),
                   "--participants: expected a whole number from 2 to 1000, got \"99999999999999999999\""));
    CHECK(contains(calibrate({"--evaluations", "-1"}), "--evaluations: expected a whole number from 2 to 10000, got \"-1\""));
    CHECK(contains(calibrate({"--param", "stiffness_noise=nan:3"}), "--param stiffness_noise: LO: expected a number in"));
    CHECK(contains(calibrate({"--param", "stiffness_noise=0.1: 3"}), "--param stiffness_noise: HI: expected a number in"));
}

TEST_CASE("issue 49: experiment analyze --confidence 1 and --bootstrap -1 are refused showing the value") {
    TempDir dir;
    write_text(dir.file("r.csv"), "participant,stimulus,response\np1,1,1\n");
    const auto c = run_contactlab({"experiment", "analyze", dir.file("r.csv"), "--confidence", "1"});
    CHECK(c.exit_code == 2);
    CHECK(contains(c.err, "--confidence: must lie in (0, 1), e.g. 0.99, got \"1\""));
    const auto b = run_contactlab({"experiment", "analyze", dir.file("r.csv"), "--bootstrap", "-1"});
    CHECK(b.exit_code == 2);
    CHECK(contains(b.err, "--bootstrap: expected a whole number from 0 to 100000, got \"-1\""));
}

TEST_CASE("issue 49: fuzz-contact, generate bumps and edit take --seed/--jobs through the same reader") {
    TempDir dir;
    const auto f = run_contactlab({"fuzz-contact", "--rows", "10", "--seed", "-1"});
    CHECK(f.exit_code == 2);
    CHECK(contains(f.err, std::string("--seed: ") + kSeedRange + ", got \"-1\""));
    const auto j = run_contactlab({"fuzz-contact", "--rows", "10", "--jobs", "-1"});
    CHECK(j.exit_code == 2);
    CHECK(contains(j.err, std::string("--jobs: ") + kJobsRange + ", got \"-1\""));
    const auto r = run_contactlab({"fuzz-contact", "--rows", "0"});
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "--rows: expected a whole number from 1 to 9223372036854775807, got \"0\""));
    const auto g = run_contactlab({"generate", "bumps", "--seed", "18446744073709551616", "--output", dir.file("b.json")});
    CHECK(g.exit_code == 2);
    CHECK(contains(g.err, std::string("--seed: ") + kSeedRange + ", got \"18446744073709551616\""));
    // edit's --seed is read before a window opens.
    const auto e = run_contactlab({"edit", "--experiment", protocol(), "--participant", "P07", "--seed", "-1"});
    CHECK(e.exit_code == 2);
    CHECK(contains(e.err, std::string("--seed: ") + kSeedRange + ", got \"-1\""));
    CHECK(dir.entries().empty());
}

TEST_CASE("issue 49: edit --participant ../P07 is refused before a window opens (the id names the results file)") {
    TempDir dir;
    const auto e = run_contactlab({"edit", "--experiment", protocol(), "--participant", "../P07"}, dir.path().string());
    CHECK(e.exit_code == 2);
    CHECK(contains(e.err, "--participant: the id must not hold '/' (it is part of a file name), e.g. P07, got \"../P07\""));
    CHECK(dir.entries().empty());
}

TEST_CASE("issue 49: valid numbers still read as before: --seed 0, the largest seed, --jobs 0") {
    TempDir dir;
    const auto p = run_contactlab({"generate", "bumps", "--seed", "18446744073709551615", "--output", dir.file("b.json")});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 0);
    const auto q = run_contactlab({"generate", "bumps", "--seed", "0", "--output", dir.file("c.json")});
    CHECK(q.exit_code == 0);
    const auto f = run_contactlab({"fuzz-contact", "--rows", "20", "--seed", "3", "--jobs", "0"});
    INFO("stderr: " << f.err);
    CHECK(f.exit_code == 0);
}
