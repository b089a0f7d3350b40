// test_usage.cpp — `contactlab` options and subcommands: version, help, usage errors, the demo.
#include "process.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <sstream>

using namespace cli_test;

TEST_CASE("--version prints the version and, from a git checkout, the commit it was built from") {
    const auto p = run_contactlab({"--version"});
    CHECK(p.exit_code == 0);
    REQUIRE(p.out.rfind("contactlab 0.1.0", 0) == 0);
    // The commit is the checkout's HEAD (the tests run from the tree the binary was built from).
    std::string head;
    if (FILE* git = ::popen(("git -C '" + source_dir().string() + "' rev-parse HEAD 2>/dev/null").c_str(), "r")) {
        char buf[64] = {};
        if (std::fgets(buf, sizeof buf, git)) head = buf;
        ::pclose(git);
    }
    while (!head.empty() && (head.back() == '\n' || head.back() == '\r')) head.pop_back();
    if (head.size() == 40) {
        CHECK(contains(p.out, " (commit " + head));
    } else {
        CHECK(p.out == "contactlab 0.1.0\n");  // a source tree without git: no commit to name
    }
}

TEST_CASE("--help exits 0 and lists the subcommands") {
    const auto p = run_contactlab({"--help"});
    CHECK(p.exit_code == 0);
    CHECK(contains(p.out, "trace"));
    CHECK(contains(p.out, "demo"));

    const auto t = run_contactlab({"trace", "--help"});
    CHECK(t.exit_code == 0);
    CHECK(contains(t.out, "--input"));
    CHECK(contains(t.out, "--output"));
    CHECK(contains(t.out, "--stiffness"));
}

TEST_CASE("usage errors exit 2") {
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"--bogus"},                                        // unknown option
             {"frobnicate"},                                     // unknown subcommand
             {"trace", "--bogus"},                               // unknown option on trace
             {"trace", scene("flat.json"), "--output", "x.csv"}, // --input missing
             {"demo", "--scene"},                                // option without its value
         }) {
        CAPTURE(args.size());
        CAPTURE(args.empty() ? std::string() : args[0]);
        const auto p = run_contactlab(args);
        INFO("stderr: " << p.err);
        CHECK(p.exit_code == 2);
        CHECK_FALSE(p.err.empty());
    }
}

TEST_CASE("demo on scenes/block.json runs and reports ticks within the force clamp") {
    // Run from the source tree so the relative scene path resolves as a user would type it.
    const auto p = run_contactlab({"demo", "--scene", "scenes/block.json"}, source_dir().string());
    INFO("stdout: " << p.out << "\nstderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    std::istringstream lines(p.out);
    std::string line, ticks_line;
    while (std::getline(lines, line))
        if (contains(line, " ticks")) ticks_line = line;
    REQUIRE_FALSE(ticks_line.empty());
    // "<n> ticks, <c> contact changes, max |F| = <f> N, l_d in [<lo>, <hi>] mm."
    long ticks = 0;
    int changes = 0;
    double max_f = -1, lo = 0, hi = 0;
    REQUIRE(std::sscanf(ticks_line.c_str(), "%ld ticks, %d contact changes, max |F| = %lf N, l_d in [%lf, %lf] mm",
                        &ticks, &changes, &max_f, &lo, &hi) == 5);
    CHECK(ticks > 0);
    CHECK(max_f > 0.0);            // the scripted hand does reach the block
    CHECK(max_f <= 1.5 + 5e-4);    // block.json's max_force (printed to 3 decimals)
    CHECK(lo >= -10.0 - 5e-3);     // l_d on the pad: |l_d| <= L/2 = 10 mm (printed to 2 decimals)
    CHECK(hi <= 10.0 + 5e-3);
    CHECK(lo <= hi);
}
