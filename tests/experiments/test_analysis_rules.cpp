// test_analysis_rules.cpp — the analysis says what it did and never changes its test silently:
// a byte-order mark, CRLF and quoted fields, or a stray row give the plain file's paired result
// (the stray participant named); identical times give no p value; seed 002's figures by number
// of small bumps (eq. 7) and for small-only and large-only stimuli (Fig. 6) on hand-computed
// tables; label sets are bounded; 1e999 and bad UTF-8 are refused with the line.
#include "engine/experiments/analysis/analysis.hpp"
#include "engine/experiments/base/sha256.hpp"
#include "engine/experiments/analysis/statistics.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace contactlab::experiments;
using nlohmann::json;

namespace {

// Four participants, two conditions, times per participant and condition (2 trials each).
const char* kPlain =
    "participant,condition,trial,time_s\n"
    "p1,A,1,4.0\np1,A,2,4.2\np1,B,1,3.0\np1,B,2,3.1\n"
    "p2,A,1,5.0\np2,A,2,5.1\np2,B,1,4.6\np2,B,2,4.4\n"
    "p3,A,1,3.9\np3,A,2,4.0\np3,B,1,3.2\np3,B,2,3.3\n"
    "p4,A,1,6.0\np4,A,2,6.2\np4,B,1,5.9\np4,B,2,5.5\n";

const json& time_test(const json& r) {
    for (const json& c : r["comparisons"])
        if (c["measure"] == "time_s") return c;
    FAIL("no time_s comparison");
    return r;
}

bool contains_text(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
    for (std::size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) s.replace(at, from.size(), to);
    return s;
}

}  // namespace

TEST_CASE("analyze: a byte-order mark, CRLF and quoted fields give the plain file's paired test") {
    const json plain = time_test(analyze_results(parse_results_csv(kPlain, "plain.csv")));
    REQUIRE(plain["valid"] == true);
    CHECK(plain["test"]["kind"] == "paired");
    CHECK(plain["test"]["rule"] == kPairingRule);
    CHECK(plain["df"] == 3.0);
    // Per participant A - B: 1.05, 0.55, 0.7, 0.4: mean 0.675.
    CHECK(plain["mean_difference"].get<double>() == doctest::Approx(0.675));
    const std::string bom = "\xEF\xBB\xBF" + std::string(kPlain);
    const std::string crlf_quoted = replace_all(replace_all(bom, "\n", "\r\n"), "p1,", "\"p1\",");
    for (const std::string& text : {bom, crlf_quoted}) {
        const json t = time_test(analyze_results(parse_results_csv(text, "variant.csv")));
        CHECK(t["test"]["kind"] == "paired");
        CHECK(t["t"].get<double>() == plain["t"].get<double>());
        CHECK(t["p"].get<double>() == plain["p"].get<double>());
    }
}

TEST_CASE("analyze: a stray row of a participant in one condition leaves that participant out, named, not the pairing") {
    const json plain = time_test(analyze_results(parse_results_csv(kPlain, "plain.csv")));
    const json r = analyze_results(parse_results_csv(std::string(kPlain) + "p9,A,1,9.9\n", "stray.csv"));
    const json& t = time_test(r);
    CHECK(t["test"]["kind"] == "paired");
    CHECK(t["t"].get<double>() == plain["t"].get<double>());
    CHECK(t["p"].get<double>() == plain["p"].get<double>());
    REQUIRE(t["test"]["left_out"].size() == 1);
    CHECK(t["test"]["left_out"][0]["participant"] == "p9");
    CHECK(t["test"]["left_out"][0]["reason"] == "no kept rows in condition B");
    REQUIRE(r["warnings"].size() == 1);
    CHECK(r["warnings"][0] == "participant p9 left out of the paired tests: no kept rows in condition B");
}

TEST_CASE("analyze: Welch only without pairs, and then the comparison says why") {
    const json r = analyze_results(parse_results_csv("condition,time_s\nA,1\nA,2\nB,3\nB,5\n", "nopart.csv"));
    const json& t = time_test(r);
    CHECK(t["test"]["kind"] == "welch");
    CHECK(t["test"]["because"] == "no participant column");
    CHECK(t["valid"] == true);
}

TEST_CASE("analyze: identical times give no p value, with the reason, not one from round-off") {
    // 3.401 s everywhere, a different number of trials per participant and condition: a plain
    // sum's means differ in the last bits and once gave t(12) = -3.46, p = 0.005.
    std::string csv = "participant,condition,trial,time_s\n";
    for (int p = 1; p <= 7; ++p)
        for (const char* c : {"A", "B"})
            for (int k = 0; k < p + (c[0] == 'A' ? 2 : 5); ++k)
                csv += "p" + std::to_string(p) + "," + c + "," + std::to_string(k + 1) + ",3.401\n";
    const json r = analyze_results(parse_results_csv(csv, "same.csv"));
    CHECK(r["conditions"]["A"]["participants"]["p3"]["time_s"]["mean"].get<double>() == 3.401);
    const json& t = time_test(r);
    CHECK(t["valid"] == false);
    CHECK(t["p"].is_null());
    CHECK(t["t"].is_null());
    CHECK(t["undefined"] == "the differences are all equal (0): t has no variance to compare with");
}

TEST_CASE("statistics: spreads at round-off level are undefined, real ones are not") {
    const double e = std::numeric_limits<double>::epsilon();
    // Differences 0 and 4 eps x 3.401: round-off (threshold 32 eps x 3.401).
    const TTest tiny = paired_t_test({3.401, 3.401 * (1 + 4 * e), 3.401}, {3.401, 3.401, 3.401});
    CHECK_FALSE(tiny.valid);
    CHECK(std::isnan(tiny.p));
    CHECK(contains_text(tiny.undefined, "the differences are all equal to within round-off"));
    const TTest w = welch_t_test({3.401, 3.401, 3.401}, {3.401, 3.401 * (1 + 2 * e)});
    CHECK_FALSE(w.valid);
    CHECK(contains_text(w.undefined, "neither sample varies"));
    // A real spread of 1e-9 s on 3.4 s is far above 32 eps x 3.4 = 2.4e-14.
    CHECK(paired_t_test({3.401, 3.401 + 1e-9, 3.401 + 3e-9}, {3.401, 3.401, 3.401}).valid);
    // Identical values: the mean is the value, sd exactly 0.
    const Summary s = summarize(std::vector<double>(7, 3.401));
    CHECK(s.mean == 3.401);
    CHECK(s.sd == 0.0);
}

TEST_CASE("analyze: seed 002 by number of small bumps, eq. 7's average error, on a hand-computed table") {
    // stimulus = small + large bumps; response; |error|; right?
    //   2 = 2 + 0 -> 1: 1, no     2 = 1 + 1 -> 2: 0, yes    0 = 0 + 0 -> 0: 0, yes
    //   3 = 1 + 2 -> 1: 2, no     1 = 0 + 1 -> 1: 0, yes    (warm-up row left out)
    const char* csv =
        "participant,condition,trial,stimulus,response,correct,valid,warmup,small_bumps,large_bumps\n"
        "p1,F,1,4,0,0,1,1,4,0\n"
        "p1,F,2,2,1,0,1,0,2,0\n"
        "p1,F,3,2,2,1,1,0,1,1\n"
        "p1,F,4,0,0,1,1,0,0,0\n"
        "p1,F,5,3,1,0,1,0,1,2\n"
        "p1,F,6,1,1,1,1,0,0,1\n";
    const json r = analyze_results(parse_results_csv(csv, "bumps.csv"));
    const json& k = r["conditions"]["F"]["by_small_bumps"];
    REQUIRE(k.size() == 3);  // k = 0, 1, 2 (the warm-up's 4 is left out)
    CHECK(k["0"]["n"] == 2);
    CHECK(k["0"]["proportion_correct"].get<double>() == 1.0);
    CHECK(k["0"]["average_error"].get<double>() == 0.0);
    CHECK(k["1"]["n"] == 2);
    CHECK(k["1"]["proportion_correct"].get<double>() == 0.5);
    CHECK(k["1"]["average_error"].get<double>() == 1.0);  // (0 + 2) / 2
    CHECK(k["2"]["n"] == 1);
    CHECK(k["2"]["average_error"].get<double>() == 1.0);
    CHECK(k["1"]["participant_means"]["average_error"].get<double>() == 1.0);
    CHECK(r["conditions"]["F"]["small_only"]["n"] == 1);
    CHECK(r["conditions"]["F"]["small_only"]["proportion_correct"].get<double>() == 0.0);
    CHECK(r["conditions"]["F"]["large_only"]["n"] == 1);
    CHECK(r["conditions"]["F"]["large_only"]["proportion_correct"].get<double>() == 1.0);
}

TEST_CASE("analyze: seed 002 small-only and large-only accuracy compared by paired t tests (Fig. 6)") {
    // Small-only trials per participant, F then F+CLD: p1 1/2 and 2/2, p2 1/2 and 1/2, p3 0/2 and
    // 1/2: differences F - F+CLD -0.5, 0, -0.5: mean -1/3, sd sqrt(1/12), t = -2 on 2 df.
    // Large-only trials all right: no variance, no test.
    std::string csv = "participant,condition,trial,stimulus,response,small_bumps,large_bumps\n";
    auto small = [&](const char* p, const char* c, int right) {
        csv += std::string(p) + "," + c + ",1,1," + (right ? "1" : "2") + ",1,0\n";
    };
    const char* parts[] = {"p1", "p2", "p3"};
    const int f[3][2] = {{1, 0}, {1, 0}, {0, 0}}, cld[3][2] = {{1, 1}, {1, 0}, {1, 0}};
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 2; ++k) small(parts[i], "F", f[i][k]), small(parts[i], "F+CLD", cld[i][k]);
        for (const char* c : {"F", "F+CLD"}) csv += std::string(parts[i]) + "," + c + ",9,1,1,0,1\n";
    }
    const json r = analyze_results(parse_results_csv(csv, "fig6.csv"));
    CHECK(r["conditions"]["F"]["small_only"]["participant_mean"].get<double>() == doctest::Approx(1.0 / 3.0));
    CHECK(r["conditions"]["F+CLD"]["small_only"]["participant_mean"].get<double>() == doctest::Approx(2.0 / 3.0));
    const json* small_test = nullptr;
    const json* large_test = nullptr;
    for (const json& c : r["comparisons"]) {
        if (c["measure"] == "proportion_correct_small_only") small_test = &c;
        if (c["measure"] == "proportion_correct_large_only") large_test = &c;
    }
    REQUIRE(small_test);
    REQUIRE(large_test);
    CHECK((*small_test)["test"]["kind"] == "paired");
    CHECK((*small_test)["mean_difference"].get<double>() == doctest::Approx(-1.0 / 3.0));
    CHECK((*small_test)["t"].get<double>() == doctest::Approx(-2.0));
    CHECK((*small_test)["df"] == 2.0);
    CHECK((*large_test)["valid"] == false);
    CHECK((*large_test)["p"].is_null());
}

TEST_CASE("analyze: thousands of distinct labels are refused with a reason, 1e999 and bad UTF-8 with the line") {
    std::string csv = "stimulus,response\n";
    for (int i = 0; i < 3000; ++i) csv += std::to_string(i) + ".5,1\n";
    CHECK_THROWS_WITH_AS(analyze_results(parse_results_csv(csv, "many.csv")),
                         doctest::Contains("many.csv: line 202, column stimulus: more than 200 distinct stimulus labels"),
                         ExperimentError);
    CHECK_THROWS_WITH_AS(analyze_results(parse_results_csv("stimulus,response\n1,1\n1e999,1\n", "big.csv")),
                         "big.csv: line 3, column stimulus: \"1e999\" is out of the range of a double", ExperimentError);
    CHECK_THROWS_WITH_AS(parse_results_csv("stimulus,response\n1,1\n2,\xC3\x28\n", "latin.csv"),
                         "latin.csv: line 3: not UTF-8 (save the file as UTF-8)", ExperimentError);
    // Valid UTF-8 labels are labels.
    CHECK_NOTHROW(analyze_results(parse_results_csv("stimulus,response\n\xC3\xA9t\xC3\xA9,1\n", "utf8.csv")));
}

TEST_CASE("sha256: the FIPS 180-4 examples") {
    CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
          "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}
