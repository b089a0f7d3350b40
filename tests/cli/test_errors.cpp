// test_errors.cpp — bad input to `contactlab trace`: exit code 2, a message naming the file and the
// line (or the scene path, or the option), and no output file.
#include "trace_fixture.hpp"

#include <doctest/doctest.h>

using namespace cli_test;

namespace {

// Runs trace on `input` and checks the common contract of a bad CSV: exit 2, stderr names the
// input file with ":<line>", and nothing is written beside it (no output, no temporary).
ProcessResult expect_csv_error(const std::string& input, int line) {
    TempDir dir;
    const TraceRun r = run_trace(dir, scene("flat.json"), input);
    const std::string where = dir.file("in.csv") + ":" + std::to_string(line);
    INFO("stderr: " << r.proc.err);
    CHECK(r.proc.exit_code == 2);
    CHECK(contains(r.proc.err, where));
    CHECK_FALSE(r.output_exists);
    CHECK(dir.entries() == std::vector<std::string>{"in.csv"});
    return r.proc;
}

const char* kGood = "t,x,y,phi\n0,0.01,0.05,0\n0.001,0.01,0.04,0\n";

}  // namespace

TEST_CASE("bad csv: wrong header is reported on line 1") {
    const auto p = expect_csv_error("t,x,y\n0,0.01,0.05\n", 1);
    CHECK(contains(p.err, "t,x,y,phi"));  // says what was expected
}

TEST_CASE("bad csv: a non-number on line 4") {
    const auto p = expect_csv_error(std::string(kGood) + "0.002,abc,0.03,0\n", 4);
    CHECK(contains(p.err, "abc"));
}

TEST_CASE("bad csv: too few fields or too many") {
    expect_csv_error(std::string(kGood) + "0.002,0.01,0.03\n", 4);
    expect_csv_error("t,x,y,phi\n0,0.01\n", 2);
    expect_csv_error(std::string(kGood) + "0.002,0.01,0.03,0,7\n", 4);
    expect_csv_error(std::string(kGood) + "0.002,0.01,,0\n", 4);  // an empty field
}

TEST_CASE("bad csv: nan and inf values are rejected") {
    for (const char* v : {"nan", "NaN", "inf", "-inf", "infinity", "1e999"}) {
        CAPTURE(v);
        expect_csv_error(std::string(kGood) + "0.002,0.01," + v + ",0\n", 4);
        expect_csv_error(std::string("t,x,y,phi\n") + v + ",0.01,0.05,0\n", 2);
    }
}

TEST_CASE("bad csv: time not increasing") {
    const auto p = expect_csv_error(std::string(kGood) + "0.001,0.01,0.03,0\n", 4);  // repeated
    CHECK(contains(p.err, "does not increase"));
    expect_csv_error(std::string(kGood) + "0.0005,0.01,0.03,0\n", 4);  // backwards
    // Tiny times are named with the digits that tell them apart, not "0.000000".
    const auto q = expect_csv_error("t,x,y,phi\n1e-07,0,0.05,0\n1e-07,0,0.05,0\n", 3);
    CHECK(contains(q.err, "1e-07"));
}

TEST_CASE("bad csv: empty file") {
    const auto p = expect_csv_error("", 1);
    CHECK(contains(p.err, "empty"));
}

TEST_CASE("bad csv: missing input file is exit 2 and names the file") {
    TempDir dir;
    const std::string out = dir.file("out.csv");
    const std::string in = dir.file("no-such.csv");
    const auto p = run_contactlab({"trace", scene("flat.json"), "--input", in, "--output", out});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, in));
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("bad csv: an existing output file is left untouched") {
    TempDir dir;
    write_text(dir.file("out.csv"), "previous contents\n");
    const TraceRun r = run_trace(dir, scene("flat.json"), std::string(kGood) + "0.002,abc,0.03,0\n");
    CHECK(r.proc.exit_code == 2);
    CHECK(read_text(dir.file("out.csv")) == "previous contents\n");
    CHECK(dir.entries() == std::vector<std::string>{"in.csv", "out.csv"});
}

TEST_CASE("bad scene: a zero-length line is named by its path in the file") {
    TempDir dir;
    const std::string bad = dir.file("bad.json");
    write_text(bad, R"({
  "version": 1,
  "finger": { "radius": 0.026, "length": 0.02 },
  "contours": [ { "closed": false, "segments": [
    { "type": "line", "from": [-0.3, 0.0], "to": [0.0, 0.0] },
    { "type": "line", "from": [0.0, 0.0], "to": [0.0, 0.0] },
    { "type": "line", "from": [0.0, 0.0], "to": [0.3, 0.0] } ] } ],
  "force": { "model": "spring", "stiffness": 1000.0, "max_force": 1.5 },
  "contact_location": { "rule": "centroid" }
}
)");
    write_text(dir.file("in.csv"), kGood);
    const auto p = run_contactlab({"trace", bad, "--input", dir.file("in.csv"), "--output", dir.file("out.csv")});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "contours[0].segments[1]: zero-length line"));
    CHECK(contains(p.err, bad));
    CHECK_FALSE(fs::exists(dir.file("out.csv")));
}

TEST_CASE("bad scene: missing scene file is exit 2 and names the file") {
    TempDir dir;
    write_text(dir.file("in.csv"), kGood);
    const std::string missing = dir.file("missing.json");
    const auto p = run_contactlab({"trace", missing, "--input", dir.file("in.csv"), "--output", dir.file("out.csv")});
    INFO("stderr: " << p.err);
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, missing));
    CHECK_FALSE(fs::exists(dir.file("out.csv")));

    const auto d = run_contactlab({"demo", "--scene", missing});
    CHECK(d.exit_code == 2);
    CHECK(contains(d.err, missing));
}

TEST_CASE("absurd overrides are exit 2 with a message naming the option") {
    struct Case {
        std::vector<std::string> args;
        const char* option;
        const char* field;
    };
    const std::vector<Case> cases = {
        {{"--radius", "-1"}, "--radius", "finger.radius"},
        {{"--radius=-1"}, "--radius", "finger.radius"},
        {{"--radius", "0"}, "--radius", "finger.radius"},
        {{"--stiffness", "1e12"}, "--stiffness", "force.stiffness"},
        {{"--stiffness", "-5"}, "--stiffness", "force.stiffness"},
        {{"--length", "1"}, "--length", "finger.length"},  // 1 m pad on a 2 pi 0.026 = 0.163 m circle
        {{"--max-force", "0"}, "--max-force", "force.max_force"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args[0]);
        TempDir dir;
        std::vector<std::string> extra = c.args;
        const TraceRun r = run_trace(dir, scene("flat.json"), kGood, extra);
        INFO("stderr: " << r.proc.err);
        CHECK(r.proc.exit_code == 2);
        CHECK(contains(r.proc.err, c.option));
        CHECK(contains(r.proc.err, c.field));
        CHECK_FALSE(r.output_exists);
    }
    // A value that is not a number is a usage error.
    TempDir dir;
    const TraceRun r = run_trace(dir, scene("flat.json"), kGood, {"--stiffness", "stiff"});
    CHECK(r.proc.exit_code == 2);
    CHECK(contains(r.proc.err, "--stiffness"));
    CHECK_FALSE(r.output_exists);
}
