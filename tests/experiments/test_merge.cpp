// test_merge.cpp — `contactlab experiment merge`: runs of one study split by participants (as a
// cluster's array tasks make them) merge into the same bytes one run of all of them writes, traces
// included, and its meta lists every source; a bad merge (another seed or protocol, a participant
// run twice with other rows, an unfinished or truncated source, an existing output) exits 2 naming
// the file and what differs, and writes nothing.
#include "process.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

using namespace cli_test;

namespace {

const std::string kProtocol = "scenes/experiments/004-surface-orientation.json";  // seed 004: ~1 s a participant

std::string protocol_path() { return (source_dir() / kProtocol).string(); }

void run(const std::vector<std::string>& args) {
    const ProcessResult r = run_contactlab(args);
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
}

void run_participants(const TempDir& dir, const std::string& spec, const std::string& out, const std::string& seed = "1",
                      bool traces = false) {
    std::vector<std::string> args = {"experiment", "run", protocol_path(), "--participants", spec, "--seed", seed,
                                     "--jobs", "1", "-o", dir.file(out)};
    if (!traces) args.push_back("--no-traces");
    run(args);
}

void refused(const std::vector<std::string>& args, const std::string& says, const std::string& output) {
    const ProcessResult r = run_contactlab(args);
    CAPTURE(r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(says) != std::string::npos);
    CHECK_FALSE(fs::exists(output));
}

}  // namespace

TEST_CASE("experiment merge: two participant ranges give the bytes of one run of both, traces and all") {
    TempDir dir;
    run_participants(dir, "sim:1-3", "all.csv", "1", true);
    run_participants(dir, "sim:3-3", "c.csv", "1", true);
    run_participants(dir, "sim:1-2", "a.csv", "1", true);
    // Given out of order: the merged rows follow the participants' numbers, as one run's do.
    const ProcessResult m = run_contactlab({"experiment", "merge", dir.file("c.csv"), dir.file("a.csv"), "-o", dir.file("m.csv")});
    INFO(m.err);
    REQUIRE(m.exit_code == 0);
    CHECK(read_text(dir.file("m.csv")) == read_text(dir.file("all.csv")));
    std::size_t traces = 0;
    for (const auto& e : fs::directory_iterator(dir.file("all.csv.traces"))) {
        const fs::path copy = fs::path(dir.file("m.csv.traces")) / e.path().filename();
        REQUIRE(fs::exists(copy));
        CHECK(read_text(copy.string()) == read_text(e.path().string()));
        ++traces;
    }
    CHECK(traces == 3 * 180);  // 2 templates x 9 pairs x 10 repetitions a participant
    // The meta: a run's (analyze reads it), its participants the union, every source listed.
    const auto meta = nlohmann::json::parse(read_text(dir.file("m.csv.meta.json")));
    const auto one = nlohmann::json::parse(read_text(dir.file("all.csv.meta.json")));
    CHECK(meta["participants"] == one["participants"]);
    CHECK(meta["rows"] == one["rows"]);
    for (const char* key : {"protocol_sha256", "seed", "device", "servo_rate_hz", "traces", "contactlab_version"})
        CHECK(meta[key] == one[key]);
    REQUIRE(meta["merged_from"].size() == 2);
    CHECK(meta["merged_from"][0]["file"] == dir.file("c.csv"));
    CHECK(meta["merged_from"][0]["sha256"].get<std::string>().size() == 64);
    CHECK(meta["merged_from"][1]["participants"] == nlohmann::json::array({"sim1", "sim2"}));
    CHECK(meta["merged_from"][1]["command"].get<std::string>().find("sim:1-2") != std::string::npos);
    CHECK(meta["merged_from"][1].contains("host"));
    const ProcessResult a = run_contactlab({"experiment", "analyze", dir.file("m.csv")});
    CHECK(a.exit_code == 0);
    CHECK(a.err.find("warning") == std::string::npos);
}

TEST_CASE("experiment merge: a participant in two files is taken once when its rows are the same bytes") {
    TempDir dir;
    run_participants(dir, "sim:1-2", "a.csv");
    run_participants(dir, "sim:2-3", "b.csv");
    run_participants(dir, "sim:1-3", "all.csv");
    run({"experiment", "merge", dir.file("a.csv"), dir.file("b.csv"), "-o", dir.file("m.csv")});
    CHECK(read_text(dir.file("m.csv")) == read_text(dir.file("all.csv")));
}

TEST_CASE("experiment merge refuses another study, other rows, an unfinished or truncated file, and an existing output") {
    TempDir dir;
    run_participants(dir, "sim:1-1", "a.csv");
    run_participants(dir, "sim:2-2", "b.csv");
    const std::string out = dir.file("m.csv");
    // Another seed: another study.
    run_participants(dir, "sim:2-2", "seed2.csv", "2");
    refused({"experiment", "merge", dir.file("a.csv"), dir.file("seed2.csv"), "-o", out}, "another seed", out);
    // Another protocol: the same task with one more repetition.
    std::string text = read_text(protocol_path());
    const auto at = text.find("\"repetitions\": 10");
    REQUIRE(at != std::string::npos);
    text.replace(at, 17, "\"repetitions\": 11");
    write_text(dir.file("p11.json"), text);
    run({"experiment", "run", dir.file("p11.json"), "--participants", "sim:3-3", "--no-traces", "-o", dir.file("p11.csv")});
    refused({"experiment", "merge", dir.file("a.csv"), dir.file("p11.csv"), "-o", out}, "another protocol", out);
    // The same participant with other rows (one response changed, the meta's row count kept).
    fs::copy_file(dir.file("b.csv"), dir.file("b2.csv"));
    fs::copy_file(dir.file("b.csv.meta.json"), dir.file("b2.csv.meta.json"));
    std::string rows = read_text(dir.file("b2.csv"));
    // The first row's response (the sixth field): A <-> B.
    const auto row1 = rows.find('\n') + 1;
    std::size_t field = row1;
    for (int k = 0; k < 5; ++k) field = rows.find(',', field) + 1;
    REQUIRE((rows[field] == 'A' || rows[field] == 'B'));
    rows[field] = rows[field] == 'A' ? 'B' : 'A';
    write_text(dir.file("b2.csv"), rows);
    refused({"experiment", "merge", dir.file("b.csv"), dir.file("b2.csv"), "-o", out}, "with other rows", out);
    // A truncated file: its last row cut off.
    std::string cut = read_text(dir.file("b.csv"));
    cut.erase(cut.rfind('\n', cut.size() - 2) + 1);
    write_text(dir.file("b.csv"), cut);
    refused({"experiment", "merge", dir.file("a.csv"), dir.file("b.csv"), "-o", out}, "truncated", out);
    // An unfinished run (killed before it finished: finished_utc null).
    auto meta = nlohmann::json::parse(read_text(dir.file("a.csv.meta.json")));
    meta["finished_utc"] = nullptr;
    write_text(dir.file("u.csv.meta.json"), meta.dump(2));
    fs::copy_file(dir.file("a.csv"), dir.file("u.csv"));
    refused({"experiment", "merge", dir.file("u.csv"), "-o", out}, "unfinished", out);
    // No meta: which run made it is unknown.
    fs::copy_file(dir.file("a.csv"), dir.file("bare.csv"));
    refused({"experiment", "merge", dir.file("bare.csv"), "-o", out}, "no ", out);
    // An existing output is kept unless --overwrite.
    write_text(out, "keep me\n");
    const ProcessResult r = run_contactlab({"experiment", "merge", dir.file("a.csv"), "-o", out});
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--overwrite") != std::string::npos);
    CHECK(read_text(out) == "keep me\n");
    run({"experiment", "merge", dir.file("a.csv"), "-o", out, "--overwrite"});
    CHECK(read_text(out) == read_text(dir.file("a.csv")));
}
