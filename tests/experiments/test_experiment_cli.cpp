// test_experiment_cli.cpp — the real `contactlab experiment` commands: analyze's printed figures,
// JSON and report with plots, and its errors (exit 2, file and line named).
#include "process.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

using namespace cli_test;

TEST_CASE("experiment analyze: seed 004 Table I from a results file, as JSON and as a report with plots") {
    TempDir dir;
    std::string csv = "participant,condition,trial,stimulus,response,correct,valid,warmup,e,k\n";
    int trial = 0;
    auto rows = [&](const char* stim, const char* resp, int n, int correct, const char* e) {
        for (int i = 0; i < n; ++i, ++trial)
            csv += "p" + std::to_string(trial % 5) + ",e" + e + "," + std::to_string(trial) + "," + stim + "," + resp + "," +
                   std::to_string(correct) + ",1,0," + e + ",0.75\n";
    };
    rows("45", "A", 41, 1, "0.40");
    rows("45", "B", 9, 0, "0.40");
    rows("135", "A", 3, 0, "0.40");
    rows("135", "B", 47, 1, "0.40");
    rows("45", "A", 25, 1, "1.00");  // e = 1: answers at chance, phi 0
    rows("45", "B", 25, 0, "1.00");
    rows("135", "A", 25, 0, "1.00");
    rows("135", "B", 25, 1, "1.00");
    write_text(dir.file("r.csv"), csv);
    const auto p = run_contactlab({"experiment", "analyze", dir.file("r.csv"), "--json", dir.file("r.json"), "--report",
                                   dir.file("report")});
    INFO("stderr: " << p.err << "\nstdout: " << p.out);
    REQUIRE(p.exit_code == 0);
    CHECK(contains(p.out, "phi 0.766"));
    const auto j = nlohmann::json::parse(read_text(dir.file("r.json")));
    CHECK(j["conditions"]["e0.40"]["cramers_phi"].get<double>() == doctest::Approx(0.765532).epsilon(1e-6));
    CHECK(j["conditions"]["e1.00"]["cramers_phi"].get<double>() == doctest::Approx(0.0).epsilon(1e-12));
    CHECK(j["comparisons"].size() == 2);  // proportion correct and IT, paired over the 5 participants
    const std::string md = read_text(dir.file("report/report.md"));
    CHECK(contains(md, "| 45 | 41 | 9 |"));
    // The seed's own figure (experiment_figures.hpp), with its caption.
    CHECK(contains(md, "![Orientation matched to the field: Cramer's phi (seed 004)](seed004_phi.png)"));
    CHECK(contains(md, "Each point: Cramer's phi of the 2 x 2 table"));
    CHECK(std::filesystem::file_size(dir.file("report/seed004_phi.png")) > 1000);
    CHECK(contains(md, "![Confusion: e0.40](confusion_1.png)"));
    CHECK(std::filesystem::file_size(dir.file("report/confusion_1.png")) > 1000);
}

TEST_CASE("experiment analyze: a bad results file exits 2 naming the file, line and column") {
    TempDir dir;
    write_text(dir.file("bad.csv"), "stimulus,response,valid\n1,1,1\n2,2,maybe\n");
    const auto p = run_contactlab({"experiment", "analyze", dir.file("bad.csv")});
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "bad.csv: line 3, column valid: expected a number, found \"maybe\""));
    const auto q = run_contactlab({"experiment", "analyze", dir.file("missing.csv")});
    CHECK(q.exit_code == 2);
    CHECK(contains(q.err, "missing.csv: cannot open"));
}

TEST_CASE("experiment run: seed 003's protocol with two simulated participants, then analyze") {
    TempDir dir;
    const std::string out = dir.file("r.csv");
    const auto p = run_contactlab({"experiment", "run", (source_dir() / "scenes/experiments/003-curvature-cld.json").string(),
                                   "--participants", "sim:1-2", "--seed", "3", "--jobs", "2", "-o", out});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(contains(p.err, "2 participant(s), 48 trials"));
    const std::string csv = read_text(out);
    CHECK(csv.rfind("participant,condition,trial,stimulus,stimulus_unit,response,correct,valid,warmup,time_s,failed,"
                    "contact_breaks,contact_fraction,peak_force_n,touched,contact_location,device,motion\n", 0) == 0);
    CHECK(contains(csv, "sim2,B,"));
    // One trace per trial beside the results, at 100 Hz.
    CHECK(std::filesystem::exists(out + ".traces/sim1-A-1.csv"));
    CHECK(read_text(out + ".traces/sim1-A-1.csv").rfind("t,x,y,phi,contact,fx,fy,roller_l,l_d\n", 0) == 0);
    const auto a = run_contactlab({"experiment", "analyze", out, "--json", dir.file("a.json")});
    REQUIRE(a.exit_code == 0);
    const auto j = nlohmann::json::parse(read_text(dir.file("a.json")));
    CHECK(j["conditions"]["A"]["n"] == 24);
    CHECK(j["conditions"]["A"]["labels"]["stimuli"] == nlohmann::json::array({"10", "20", "30"}));
    CHECK(j["comparisons"][0]["paired"] == true);
}

TEST_CASE("experiment run: a person as participant, or a bad protocol, exits 2 and says why") {
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature-cld.json").string();
    const auto person = run_contactlab({"experiment", "run", proto, "--participant", "P07", "-o", dir.file("r.csv")});
    CHECK(person.exit_code == 2);
    CHECK(contains(person.err, "editor's experiment mode"));
    write_text(dir.file("bad.json"), "{\"format\": \"contactlab experiment protocol\", \"version\": 2}");
    const auto bad = run_contactlab({"experiment", "run", dir.file("bad.json"), "--participant", "sim", "-o", dir.file("r.csv")});
    CHECK(bad.exit_code == 2);
    CHECK(contains(bad.err, "bad.json: version: must lie in [1, 1], got 2"));
    CHECK_FALSE(std::filesystem::exists(dir.file("r.csv")));
}

TEST_CASE("experiment analyze: invalid UTF-8 and 1e999 exit 2 naming the file and line") {
    TempDir dir;
    write_text(dir.file("latin1.csv"), "participant,stimulus,response\np1,1,1\np\xe9,2,2\n");
    const auto a = run_contactlab({"experiment", "analyze", dir.file("latin1.csv"), "--json", dir.file("a.json")});
    CHECK(a.exit_code == 2);
    CHECK(contains(a.err, "latin1.csv: line 3: not UTF-8"));
    write_text(dir.file("huge.csv"), "stimulus,response\n1,1\n1e999,1\n");
    const auto b = run_contactlab({"experiment", "analyze", dir.file("huge.csv"), "--report", dir.file("rep")});
    CHECK(b.exit_code == 2);
    CHECK(contains(b.err, "huge.csv: line 3, column stimulus: \"1e999\" is out of the range of a double"));
}

TEST_CASE("experiment analyze: provenance per file in the JSON, files of different protocols pooled only when asked") {
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature-cld.json").string();
    // Two runs of different participants: one protocol, so they pool.
    for (const char* who : {"sim:1", "sim:2"}) {
        const auto r = run_contactlab({"experiment", "run", proto, "--participant", who, "-o", dir.file(std::string(who + 4) + ".csv"),
                                       "--no-traces"});
        REQUIRE(r.exit_code == 0);
    }
    const auto a = run_contactlab({"experiment", "analyze", dir.file("1.csv"), dir.file("2.csv"), "--json", dir.file("a.json")});
    INFO("stderr: " << a.err);
    REQUIRE(a.exit_code == 0);
    const auto j = nlohmann::json::parse(read_text(dir.file("a.json")));
    CHECK(j["provenance"][dir.file("1.csv")]["participants"] == nlohmann::json::array({"sim1"}));
    CHECK(j["provenance"][dir.file("2.csv")]["protocol_path"] == proto);
    CHECK(j["conditions"]["A"]["participants"].size() == 2);
    CHECK(j["comparisons"][0]["test"]["kind"] == "paired");
    // The second file's meta says another protocol: refused, then pooled with --pool-protocols.
    auto meta = nlohmann::json::parse(read_text(dir.file("2.csv.meta.json")));
    meta["protocol_sha256"] = std::string(64, '0');
    write_text(dir.file("2.csv.meta.json"), meta.dump());
    const auto refused = run_contactlab({"experiment", "analyze", dir.file("1.csv"), dir.file("2.csv")});
    CHECK(refused.exit_code == 2);
    CHECK(contains(refused.err, "come from different protocols"));
    CHECK(contains(refused.err, "--pool-protocols"));
    const auto pooled = run_contactlab({"experiment", "analyze", dir.file("1.csv"), dir.file("2.csv"), "--pool-protocols"});
    CHECK(pooled.exit_code == 0);
    CHECK(contains(pooled.err, "warning"));
}

TEST_CASE("experiment analyze: seed 002's report has the tables by number of small bumps and by bump size") {
    TempDir dir;
    std::string csv = "participant,condition,trial,stimulus,response,small_bumps,large_bumps\n";
    for (const char* p : {"p1", "p2", "p3"})
        for (const char* c : {"F", "F+CLD"})
            for (const char* row : {",1,1,1,1,0\n", ",2,2,1,0,2\n", ",3,3,2,2,1\n", ",4,0,0,0,0\n"}) csv += std::string(p) + "," + c + row;
    write_text(dir.file("b.csv"), csv);
    const auto p = run_contactlab({"experiment", "analyze", dir.file("b.csv"), "--report", dir.file("rep")});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    const std::string md = read_text(dir.file("rep/report.md"));
    CHECK(contains(md, "## By number of small bumps (seed 002 eq. 7)"));
    CHECK(contains(md, "| F | 2 | 3 | 0 | 1 |"));  // two small bumps: answered 2 of 3, always wrong by 1
    CHECK(contains(md, "## Small bumps only, large bumps only (seed 002 Fig. 6)"));
    CHECK(contains(md, "undefined: "));  // identical accuracy in both conditions: no test
    CHECK(contains(md, "b.csv | (no meta file) |"));
}

TEST_CASE("experiment run: the simulated participant feels the edge protocol through the servo and the report shows both thresholds") {
    TempDir dir;
    const std::string out = dir.file("edges.csv");
    const auto p = run_contactlab({"experiment", "run", (source_dir() / "scenes/experiments/edge-sharpness.json").string(),
                                   "--participants", "sim:1-2", "--seed", "1", "--jobs", "2", "--no-traces", "-o", out});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(contains(p.err, "2 participant(s)"));
    CHECK(contains(p.err, " 0 invalid"));
    const std::string csv = read_text(out);
    CHECK(csv.rfind("participant,condition,trial,stimulus,stimulus_unit,response,correct,valid,warmup,time_s,failed,"
                    "contact_breaks,contact_fraction,peak_force_n,touched,contact_location,device,reference_mm,comparison_interval,procedure,"
                    "target_p,reversal,estimate\n", 0) == 0);
    CHECK(contains(csv, ",mm,"));
    CHECK(contains(csv, ",sim-cld,2.5,"));
    const auto a = run_contactlab({"experiment", "analyze", out, "--psychometric", "logistic", "--bootstrap", "100", "--json",
                                   dir.file("a.json"), "--report", dir.file("report")});
    INFO("analyze stdout: " << a.out);
    REQUIRE(a.exit_code == 0);
    const auto j = nlohmann::json::parse(read_text(dir.file("a.json")));
    for (const char* c : {"force", "force+cld"}) {
        const auto& ad = j["conditions"][c]["adaptive"];
        CHECK(ad["procedure"] == "staircase 1-up-2-down");
        CHECK(ad["participants"] == 2);
        // A staircase estimate is a mean of stimuli the staircase visited: inside the protocol's range.
        CHECK(ad["estimate"].get<double>() >= 0.25);
        CHECK(ad["estimate"].get<double>() <= 8.0);
        CHECK(j["conditions"][c]["participants"]["sim1"]["adaptive"]["reversals"].get<int>() >= 1);
        CHECK(j["conditions"][c]["psychometric"]["function"] == "logistic");
        MESSAGE(std::string(c), ": median staircase estimate ", ad["estimate"].get<double>(), " mm, fitted threshold ",
                j["conditions"][c]["psychometric"].value("threshold", nlohmann::json()).dump());
    }
    const std::string md = read_text(dir.file("report/report.md"));
    CHECK(contains(md, "## Thresholds"));
    CHECK(contains(md, "| force | staircase 1-up-2-down | 0.707 | "));
    CHECK(contains(md, "| force+cld | staircase 1-up-2-down | 0.707 | "));
    // Not seed 000's figures, though the conditions share its names.
    CHECK_FALSE(contains(md, "seed000"));
    CHECK(contains(md, "](track_force.png)"));
    CHECK(std::filesystem::file_size(dir.file("report/track_force.png")) > 1000);
    CHECK(contains(md, "](psychometric_force_cld.png)"));
}

TEST_CASE("experiment run: model observers from the command line, and a bad observer exits 2 saying why") {
    TempDir dir;
    const std::string out = dir.file("obs.csv");
    const auto p = run_contactlab({"experiment", "run", (source_dir() / "scenes/experiments/edge-sharpness.json").string(),
                                   "--participants", "observer:logistic:threshold=2,scale=0.4,guess=0.5,lapse=0.02:1-3", "-o", out});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(contains(read_text(out), "\nobs3,"));
    CHECK(contains(read_text(out), ",model-observer,"));
    CHECK(contains(read_text(out + ".meta.json"), "observer:logistic:threshold=2,scale=0.4,guess=0.5,lapse=0.02"));
    const auto bad = run_contactlab({"experiment", "run", (source_dir() / "scenes/experiments/edge-sharpness.json").string(),
                                     "--participant", "observer:logistic:threshold=2", "-o", dir.file("bad.csv")});
    CHECK(bad.exit_code == 2);
    CHECK(contains(bad.err, "--participant: observer \"logistic:threshold=2\": threshold and scale are required"));
    const auto fn = run_contactlab({"experiment", "analyze", out, "--psychometric", "probit"});
    CHECK(fn.exit_code == 2);
    CHECK(contains(fn.err, "--psychometric: expected logistic, weibull or cumulative-normal, got \"probit\""));
}
