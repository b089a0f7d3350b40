// test_strict_protocol.cpp — issue 49, "Every number checked", in the protocol file: the staircase
// rule read exactly, "trials": 0 refused, a key given twice refused naming it and where, whole
// numbers never wrapped, numbers shown in messages as given (not rounded), and names that become
// file names (condition names, a live participant's id) checked when they are read. One named
// case per input the issue lists.
#include "engine/experiments/base/path_name.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/runs/live_session.hpp"
#include "process.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace contactlab::experiments;

namespace {

const char* kMinimal = R"({"format": "contactlab experiment protocol", "version": 1, "name": "x", "seed": "003",
  "task": "curvature", "conditions": [{"name": "A", "motion": "A"}], "stimuli": [0.01, 0.02], "answers": ["10", "20"]})";

// kMinimal with `from` replaced by `to`.
std::string with(const std::string& from, const std::string& to) {
    std::string s = kMinimal;
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
}

// The shipped edge-sharpness protocol (stimuli 0.25 .. 8 mm) with its "procedure" replaced.
std::string edge_with(const std::string& procedure) {
    const std::string path = (cli_test::source_dir() / "scenes" / "experiments" / "edge-sharpness.json").string();
    nlohmann::json j = nlohmann::json::parse(load_protocol(path).text);
    j["procedure"] = nlohmann::json::parse(procedure);
    return j.dump();
}

// The message a protocol is refused with, or "(accepted)".
std::string refusal(const std::string& text) {
    try {
        parse_protocol(text, "p.json");
    } catch (const ExperimentError& e) {
        return e.what();
    }
    return "(accepted)";
}

}  // namespace

TEST_CASE("issue 49: a number out of range is shown as given, not rounded (20.0000001 was printed as got 20)") {
    CHECK(refusal(edge_with(R"({"type": "staircase", "start": 20.0000001})")) ==
          "p.json: procedure.start: must lie in [0.25, 8] (within the stimuli's range), got 20.0000001");
    CHECK(refusal(with("[0.01, 0.02]", "[0.01, 0.1000000000000001]")) ==
          "p.json: stimuli[1]: must lie in [0.001, 0.1] m (the arc's height), got 0.1000000000000001");
}

TEST_CASE("issue 49: a whole number beyond a long long is not wrapped to -1 in the message") {
    CHECK(refusal(with("\"stimuli\"", "\"repetitions\": 18446744073709551615, \"stimuli\"")) ==
          "p.json: repetitions: must lie in [1, 1000], got 18446744073709551615");
    CHECK(refusal(with("\"stimuli\"", "\"repetitions\": 2.5, \"stimuli\"")) == "p.json: repetitions: expected a whole number in [1, 1000], got 2.5");
    CHECK(refusal(edge_with(R"({"type": "staircase", "halve_at": [18446744073709551615]})")) ==
          "p.json: procedure.halve_at[0]: expected a reversal number from 1 to 100, got 18446744073709551615");
}

TEST_CASE("issue 49: a condition name with a slash is refused naming conditions[0].name") {
    CHECK(refusal(with("\"name\": \"A\"", "\"name\": \"a/b\"")) ==
          "p.json: conditions[0].name: must not hold '/' (it is part of the traces' file names), got \"a/b\"");
}

TEST_CASE("issue 49: a condition name with a backslash is refused naming conditions[0].name") {
    CHECK(refusal(with("\"name\": \"A\"", R"("name": "a\\b")")) ==
          "p.json: conditions[0].name: must not hold '\\' (it is part of the traces' file names), got \"a\\b\"");
}

TEST_CASE("issue 49: a condition name with two dots is refused naming conditions[0].name") {
    CHECK(refusal(with("\"name\": \"A\"", "\"name\": \"..\"")).rfind("p.json: conditions[0].name: must not hold \"..\"", 0) == 0);
    CHECK(refusal(with("\"name\": \"A\"", "\"name\": \"x..y\"")).rfind("p.json: conditions[0].name: must not hold \"..\"", 0) == 0);
}

TEST_CASE("issue 49: a condition name with a control character is refused naming conditions[0].name") {
    CHECK(refusal(with("\"name\": \"A\"", R"("name": "a\tb")")) ==
          "p.json: conditions[0].name: must not hold a control character (it is part of the traces' file names), got \"a\\x09b\"");
    CHECK(refusal(with("\"name\": \"A\"", R"("name": "a\u0001")")).rfind("p.json: conditions[0].name: must not hold a control character", 0) == 0);
}

TEST_CASE("issue 49: an empty condition name is refused naming conditions[0].name") {
    CHECK(refusal(with("\"name\": \"A\"", "\"name\": \"\"")).rfind("p.json: conditions[0].name: must be non-empty", 0) == 0);
}

TEST_CASE("issue 49: names that may be parts of file names") {
    CHECK(path_name_problem("F+CLD") == "");
    CHECK(path_name_problem("e0.40") == "");
    CHECK(path_name_problem("P07") == "");
    CHECK(path_name_problem(".") == "");  // inside a file name it is only a dot
    CHECK(path_name_problem("") == "must not be empty");
    CHECK(path_name_problem("a/b") == "must not hold '/'");
    CHECK(path_name_problem("..") == "must not hold \"..\"");
    CHECK(path_name_problem(std::string("a\x7f")) == "must not hold a control character");
}

TEST_CASE("issue 49: a live participant id with a path in it is refused before any file is named") {
    const Protocol p = parse_protocol(kMinimal, "p.json");
    cli_test::TempDir dir;
    for (const char* id : {"../P07", "P/07", "P\\07", "..", "P\t07"})
        CHECK_THROWS_WITH_AS(LiveSession(p, id, 1, dir.file("r.csv")), doctest::Contains("--participant: the id must not hold"), ExperimentError);
    CHECK_NOTHROW(LiveSession(p, "P07", 1, dir.file("r.csv")));
}
