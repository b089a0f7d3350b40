// test_power_cli.cpp — the real `contactlab experiment power`: a pool simulated through the servo
// (seed 003's protocol on the CLD rig, 3 participants), resampled; its JSON, provenance, report, reuse of the
// pool, and errors.
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

using namespace cli_test;

TEST_CASE("experiment power: a pool through the servo, power per group size with provenance and a plot") {
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature-cld.json").string();
    const std::vector<std::string> args = {"experiment", "power", proto, "--measure", "proportion_correct", "--participants", "2-5",
                                           "--pool", "3", "--resamples", "300", "--seed", "4", "--jobs", "2",
                                           "--json", dir.file("p.json"), "--report", dir.file("rep")};
    const auto p = run_contactlab(args);
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    const auto j = nlohmann::json::parse(read_text(dir.file("p.json")));
    CHECK(j["measure"] == "proportion_correct");
    CHECK(j["pool"] == 3);
    CHECK(j["resamples"] == 300);
    CHECK(j["conditions"] == nlohmann::json::array({"A", "B"}));
    REQUIRE(j["points"].size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
        const auto& pt = j["points"][i];
        CHECK(pt["participants"] == static_cast<int>(i) + 2);
        const double power = pt["power"].get<double>();
        CHECK(power >= 0.0);
        CHECK(power <= 1.0);
        CHECK(pt["power_ci"][0].get<double>() <= power);
        CHECK(pt["power_ci"][1].get<double>() >= power);
        // The share is a count over the resamples.
        CHECK(pt["significant"].get<double>() == doctest::Approx(power * 300));
    }
    // The pool is an `experiment run` results file: its meta names the protocol and the device.
    CHECK(std::filesystem::exists(dir.file("p.pool.csv")));
    CHECK(j["pool_results"]["sha256"].get<std::string>().size() == 64);
    CHECK(j["pool_results"]["meta"]["device"] == "sim-cld");
    CHECK(j["pool_results"]["meta"]["protocol_sha256"].get<std::string>().size() == 64);
    CHECK(std::filesystem::exists(dir.file("rep/power.png")));
    CHECK(contains(read_text(dir.file("rep/report.md")), "| participants | power |"));
    // The same command again reuses the pool and gives the same figures.
    const auto again = run_contactlab(args);
    REQUIRE(again.exit_code == 0);
    CHECK(contains(again.err, "already complete"));
    CHECK(nlohmann::json::parse(read_text(dir.file("p.json")))["points"] == j["points"]);
}

TEST_CASE("experiment power: bad sizes, an unknown measure and a pool of another run exit 2 and say why") {
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature-cld.json").string();
    auto power = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = {"experiment", "power", proto, "--pool", "2", "--resamples", "50", "--json", dir.file("p.json")};
        a.insert(a.end(), extra.begin(), extra.end());
        return run_contactlab(a);
    };
    const auto one = power({"--participants", "1-4"});
    CHECK(one.exit_code == 2);
    CHECK(contains(one.err, "a paired t test needs 2"));
    const auto measure = power({"--participants", "2-3", "--measure", "loudness"});
    CHECK(measure.exit_code == 2);
    CHECK(contains(measure.err, "no per-participant loudness"));
    // The pool file now holds that run (seed 1); another seed must not silently reuse or clobber it.
    const auto other = power({"--participants", "2-3", "--seed", "9"});
    CHECK(other.exit_code == 2);
    CHECK(contains(other.err, "--overwrite"));
}

TEST_CASE("experiment power --pool-from: a merged file as the pool gives the numbers of power's own pool of those participants") {
    TempDir dir;
    const std::string proto = (source_dir() / "scenes/experiments/003-curvature-cld.json").string();
    auto ok = [](const std::vector<std::string>& args) {
        const ProcessResult r = run_contactlab(args);
        INFO(r.err);
        REQUIRE(r.exit_code == 0);
        return r;
    };
    auto power = [&](const std::string& out, std::vector<std::string> extra) {
        std::vector<std::string> a = {"experiment", "power", proto, "--measure", "proportion_correct", "--participants", "2-4",
                                      "--resamples", "200", "--seed", "4", "--jobs", "2", "--json", dir.file(out)};
        a.insert(a.end(), extra.begin(), extra.end());
        return run_contactlab(a);
    };
    REQUIRE(power("own.json", {"--pool", "3"}).exit_code == 0);
    // The same participants as two array tasks would run them, merged.
    for (const auto& [range, file] : {std::pair{"sim:1-2", "a.csv"}, std::pair{"sim:3-3", "b.csv"}, std::pair{"sim:1-4", "four.csv"}})
        ok({"experiment", "run", proto, "--participants", range, "--seed", "4", "--no-traces", "--jobs", "2", "-o", dir.file(file)});
    ok({"experiment", "merge", dir.file("a.csv"), dir.file("b.csv"), "-o", dir.file("merged.csv")});
    const ProcessResult merged = power("merged.json", {"--pool-from", dir.file("merged.csv")});
    INFO(merged.err);
    REQUIRE(merged.exit_code == 0);
    CHECK(contains(merged.err, "pool of 3 of its 3 participants from " + dir.file("merged.csv")));
    // --pool N takes the file's first N participants.
    REQUIRE(power("first3.json", {"--pool-from", dir.file("four.csv"), "--pool", "3"}).exit_code == 0);
    const auto own = nlohmann::json::parse(read_text(dir.file("own.json")));
    for (const char* out : {"merged.json", "first3.json"}) {
        CAPTURE(out);
        const auto j = nlohmann::json::parse(read_text(dir.file(out)));
        CHECK(j["pool"] == 3);
        CHECK(j["points"] == own["points"]);
        CHECK(j["pool_effect"] == own["pool_effect"]);
        CHECK(j["left_out"] == own["left_out"]);
    }
    // Provenance: the file given and its bytes' hash (the merged file is own's pool, byte for byte).
    const auto m = nlohmann::json::parse(read_text(dir.file("merged.json")));
    CHECK(m["pool_results"]["file"] == dir.file("merged.csv"));
    CHECK(m["pool_results"]["sha256"] == own["pool_results"]["sha256"]);
    CHECK(m["pool_results"]["meta"]["merged_from"].size() == 2);
    CHECK_FALSE(std::filesystem::exists(dir.file("merged.pool.csv")));  // nothing ran

    // Refused, exit 2 naming the file: too few participants, another protocol, an unfinished run.
    const ProcessResult few = power("x.json", {"--pool-from", dir.file("merged.csv"), "--pool", "4"});
    CHECK(few.exit_code == 2);
    CHECK(contains(few.err, "--pool-from " + dir.file("merged.csv") + ": holds 3 participants, 4 asked"));
    const std::string other = (source_dir() / "scenes/experiments/004-surface-orientation.json").string();
    const ProcessResult wrong = run_contactlab({"experiment", "power", other, "--participants", "2-3", "--json", dir.file("x.json"),
                                                "--pool-from", dir.file("merged.csv")});
    CHECK(wrong.exit_code == 2);
    CHECK(contains(wrong.err, "--pool-from " + dir.file("merged.csv") + ": a run of another protocol"));
    auto meta = nlohmann::json::parse(read_text(dir.file("a.csv.meta.json")));
    meta["finished_utc"] = nullptr;
    write_text(dir.file("a.csv.meta.json"), meta.dump(2));
    const ProcessResult unfinished = power("x.json", {"--pool-from", dir.file("a.csv")});
    CHECK(unfinished.exit_code == 2);
    CHECK(contains(unfinished.err, dir.file("a.csv") + ": an unfinished run"));
    CHECK_FALSE(std::filesystem::exists(dir.file("x.json")));
}

TEST_CASE("experiment power --hand: the pool runs with the hand named, a --pool-from file of another hand is refused") {
    TempDir dir;
    // Seed 000's task, whose person has a hand that moves by feel; its protocol made to name none.
    std::string text = read_text((source_dir() / "scenes/experiments/000-contour-following.json").string());
    const auto model = text.find("\"model\": \"feel\", ");
    REQUIRE(model != std::string::npos);
    write_text(dir.file("slide.json"), text.erase(model, std::string("\"model\": \"feel\", ").size()));
    const std::string proto = dir.file("slide.json");
    auto power = [&](const std::string& out, std::vector<std::string> extra) {
        std::vector<std::string> a = {"experiment", "power", proto, "--measure", "time_s", "--participants", "2-3",
                                      "--pool", "2", "--resamples", "50", "--jobs", "2", "--json", dir.file(out)};
        a.insert(a.end(), extra.begin(), extra.end());
        return run_contactlab(a);
    };
    // The protocol names no hand (scripted); --hand feel is the pool's, in its meta and the JSON's provenance.
    const ProcessResult feel = power("feel.json", {"--hand", "feel"});
    INFO(feel.err);
    REQUIRE(feel.exit_code == 0);
    CHECK(nlohmann::json::parse(read_text(dir.file("feel.pool.csv.meta.json")))["hand"] == "feel");
    CHECK(nlohmann::json::parse(read_text(dir.file("feel.json")))["pool_results"]["meta"]["hand"] == "feel");
    // The same pool file asked with the protocol's own hand is another run: refused unless --overwrite.
    const ProcessResult again = run_contactlab({"experiment", "power", proto, "--measure", "proportion_correct", "--participants",
                                                "2-3", "--pool", "2", "--resamples", "50", "--json", dir.file("feel.json")});
    CHECK(again.exit_code == 2);
    CHECK(contains(again.err, "another hand"));
    // A finished file of the feel hand as the pool: taken with --hand feel or no --hand, refused with --hand scripted.
    REQUIRE(power("from.json", {"--pool-from", dir.file("feel.pool.csv"), "--hand", "feel"}).exit_code == 0);
    REQUIRE(power("plain.json", {"--pool-from", dir.file("feel.pool.csv")}).exit_code == 0);
    const ProcessResult other = power("x.json", {"--pool-from", dir.file("feel.pool.csv"), "--hand", "scripted"});
    CHECK(other.exit_code == 2);
    CHECK(contains(other.err, "--pool-from " + dir.file("feel.pool.csv") + ": its participants moved with the feel hand, --hand asks scripted"));
    const ProcessResult bogus = power("x.json", {"--hand", "telepathic"});
    CHECK(bogus.exit_code == 2);
    CHECK(contains(bogus.err, "--hand: expected scripted or feel, got \"telepathic\""));
    // Seed 003's task has no hand that moves by feel: refused, naming the file, before any pool runs.
    const std::string curvature = (source_dir() / "scenes/experiments/003-curvature-cld.json").string();
    const ProcessResult none = run_contactlab({"experiment", "power", curvature, "--measure", "proportion_correct", "--participants",
                                               "2-3", "--pool", "2", "--hand", "feel", "--json", dir.file("none.json")});
    CHECK(none.exit_code == 2);
    CHECK(contains(none.err, "--hand feel: " + curvature + " is a curvature protocol"));
    CHECK_FALSE(std::filesystem::exists(dir.file("none.pool.csv")));
    CHECK_FALSE(std::filesystem::exists(dir.file("x.json")));
}
