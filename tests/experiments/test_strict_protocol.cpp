// test_strict_protocol.cpp — issue 49, "Every number checked", in the protocol file: the staircase
// rule read exactly, "trials": 0 refused, a key given twice refused naming it and where, whole
// numbers never wrapped, numbers shown in messages as given (not rounded), and names that become
// file names (condition names, a live participant's id) checked when they are read. One named
// case per input the issue lists.
#include "engine/experiments/base/path_name.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/experiments/protocol/protocol.hpp"
#include "engine/experiments/runs/live_session.hpp"
#include "minimal_protocol.hpp"
#include "process.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace contactlab::experiments;

namespace {

using protocol_test::kMinimal;
using protocol_test::with;

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

std::string rule_refusal(const std::string& rule) {
    return refusal(edge_with(R"({"type": "staircase", "rule": ")" + rule + R"("})"));
}

const char* kRuleMessage = "p.json: procedure.rule: expected \"1-up-N-down\" with N from 1 to 5, one digit";

}  // namespace

TEST_CASE("issue 49: staircase rule 1-up-2.5-down is refused (sscanf read it as 1-up-2-down)") {
    const std::string m = rule_refusal("1-up-2.5-down");
    CHECK(m.rfind(kRuleMessage, 0) == 0);
    CHECK(cli_test::contains(m, "got \"1-up-2.5-down\""));
}

TEST_CASE("issue 49: staircase rules 1-up-2abc and 1-up-2abc-down are refused") {
    CHECK(rule_refusal("1-up-2abc").rfind(kRuleMessage, 0) == 0);
    CHECK(rule_refusal("1-up-2abc-down").rfind(kRuleMessage, 0) == 0);
}

TEST_CASE("issue 49: staircase rule with a blank before N is refused") {
    CHECK(rule_refusal("1-up- 2-down").rfind(kRuleMessage, 0) == 0);
}

TEST_CASE("issue 49: staircase rule 1-up-+2-down (a sign) is refused") {
    CHECK(rule_refusal("1-up-+2-down").rfind(kRuleMessage, 0) == 0);
}

TEST_CASE("issue 49: staircase rules 1-up-02-down and 01-up-2-down (leading zeros) are refused") {
    CHECK(rule_refusal("1-up-02-down").rfind(kRuleMessage, 0) == 0);
    CHECK(rule_refusal("01-up-2-down").rfind(kRuleMessage, 0) == 0);
    CHECK(rule_refusal("1-up-6-down").rfind(kRuleMessage, 0) == 0);
    CHECK(rule_refusal("1-up-0-down").rfind(kRuleMessage, 0) == 0);
}

TEST_CASE("issue 49: the staircase rules 1-up-1-down .. 1-up-5-down still read") {
    for (int n = 1; n <= 5; ++n) {
        const Protocol p = parse_protocol(edge_with(R"({"type": "staircase", "rule": "1-up-)" + std::to_string(n) + R"(-down"})"), "p.json");
        CHECK(p.procedure.down == n);
    }
}

TEST_CASE("issue 49: trials 0 is refused with its range") {
    CHECK(refusal(with("\"stimuli\"", "\"trials\": 0, \"stimuli\"")) == "p.json: trials: must lie in [1, 100000], got 0");
    CHECK(parse_protocol(with("\"stimuli\"", "\"trials\": 4, \"stimuli\""), "p.json").trials == 4);
    CHECK(parse_protocol(kMinimal, "p.json").trials == 0);  // absent: repetitions x stimuli
}

TEST_CASE("issue 49: a key given twice at the top of a protocol is refused naming the key") {
    CHECK(refusal(with("\"stimuli\"", "\"trials\": 4, \"trials\": 5, \"stimuli\"")) ==
          "p.json: key \"trials\" given twice (a key appears once in its object: JSON readers keep either one)");
}

TEST_CASE("issue 49: a key given twice inside conditions[0] is refused naming the key and where") {
    CHECK(refusal(with("\"name\": \"A\"", "\"name\": \"A\", \"name\": \"B\"")).rfind("p.json: conditions[0]: key \"name\" given twice", 0) ==
          0);
    // The second element of an array, and an object inside an object.
    CHECK(refusal(with("[{\"name\": \"A\", \"motion\": \"A\"}]",
                       "[{\"name\": \"A\", \"motion\": \"A\"}, {\"name\": \"B\", \"motion\": \"B\", \"motion\": \"A\"}]"))
              .rfind("p.json: conditions[1]: key \"motion\" given twice", 0) == 0);
    CHECK(refusal(with("\"stimuli\"", "\"hand\": {\"speed\": 0.1, \"speed\": 0.2}, \"stimuli\"")).rfind("p.json: hand: key \"speed\" given twice", 0) ==
          0);
    // The same key in two different objects is no duplicate.
    CHECK(refusal(with("[{\"name\": \"A\", \"motion\": \"A\"}]", "[{\"name\": \"A\", \"motion\": \"A\"}, {\"name\": \"B\", \"motion\": \"B\"}]")) ==
          "(accepted)");
}

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
