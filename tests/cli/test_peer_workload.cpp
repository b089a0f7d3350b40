// test_peer_workload.cpp — `contactlab generate peer-workload`: the bench's dense case as files
// (issue 18), checked against the sinusoid it claims to be, and timed back through
// `contactlab bench --scene --input`.
#include "csv.hpp"
#include "process.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace cli_test;

namespace {
// The profile: 1 cm amplitude, 10 cm wavelength over 0.4 m (m).
double height(double x) { return 0.01 * std::sin(2.0 * std::numbers::pi * x / 0.1); }
double slope(double x) { return 0.01 * 2.0 * std::numbers::pi / 0.1 * std::cos(2.0 * std::numbers::pi * x / 0.1); }
std::size_t count_of(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}
}  // namespace

TEST_CASE("generate peer-workload: N line segments on the sinusoid, a 4000-tick stroke 1 mm deep along its normal") {
    TempDir dir;
    const std::string scene_path = dir.file("peer.json"), trace_path = dir.file("peer.csv");
    const auto p = run_contactlab({"generate", "peer-workload", "--segments", "250", "-o", scene_path, "--trace", trace_path});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(count_of(read_text(scene_path), "\"line\"") == 250);
    const Csv csv = parse_csv(read_text(trace_path));
    CHECK(csv.header == "t,x,y,phi");
    REQUIRE(csv.rows.size() == 4001);
    // Stroke sample k (row k + 1): the finger centre R - 1 mm = 25 mm along the profile's normal at
    // x = 0.1 + 0.2 k / 4000, pad facing down (phi 0), one per millisecond (5 cm/s along x).
    for (const std::size_t k : {std::size_t{0}, std::size_t{1234}, std::size_t{3999}}) {
        const double x0 = 0.1 + 0.2 * static_cast<double>(k) / 4000.0;
        const double norm = std::hypot(slope(x0), 1.0);
        CAPTURE(k);
        const std::vector<double>& row = csv.rows[k + 1];
        CHECK(row[0] == doctest::Approx(1e-3 * static_cast<double>(k + 1)).epsilon(1e-12));
        CHECK(std::abs(row[1] - (x0 - 0.025 * slope(x0) / norm)) <= 1e-12);
        CHECK(std::abs(row[2] - (height(x0) + 0.025 / norm)) <= 1e-12);
        CHECK(row[3] == 0.0);
    }
    // Row 0: 5 cm above the stroke's start, in free space, so the trace starts outside the solid.
    CHECK(csv.rows[0][0] == 0.0);
    CHECK(csv.rows[0][1] == csv.rows[1][1]);
    CHECK(std::abs(csv.rows[0][2] - (csv.rows[1][2] + 0.05)) <= 1e-15);
    // The same files time through bench --scene: the pad is pressed in on every stroke tick.
    const auto b = run_contactlab({"bench", "--scene", scene_path, "--input", trace_path, "--passes", "1"});
    INFO("bench stderr: " << b.err);
    REQUIRE(b.exit_code == 0);
    CHECK(b.out.find("4001 samples x 1 passes, 100 % in contact") != std::string::npos);
    CHECK(b.out.find("ns per tick: median") != std::string::npos);
    // ... and where the time goes, by named stage (a second, profiled pass).
    CHECK(b.out.find("stages, mean ns per tick") != std::string::npos);
    CHECK(b.out.find(", walk ") != std::string::npos);
    // The tail: p99.9 beside the median and the ticks that miss a period, and the slowest ticks' stages.
    CHECK(b.out.find("p99.9 ") != std::string::npos);
    CHECK(b.out.find("ticks over 100 us: ") != std::string::npos);
    CHECK(b.out.find("the slowest 4 tick(s) of that pass") != std::string::npos);  // 0.1 % of 4,001

    // --ticks: one row per tick, pass and sample in order, each stage's ns from the profiled replay.
    const std::string ticks_path = dir.file("ticks.csv");
    const auto t = run_contactlab({"bench", "--scene", scene_path, "--input", trace_path, "--passes", "2", "--ticks", ticks_path});
    INFO("bench --ticks stderr: " << t.err);
    REQUIRE(t.exit_code == 0);
    std::ifstream in(ticks_path);
    std::string line;
    REQUIRE(std::getline(in, line));
    CHECK(line == "pass,sample,ns,contact,gather_ns,pieces_ns,walk_ns,contact_ns,anticipate_ns,profiled_ns");
    std::size_t rows = 0, in_contact = 0;
    std::vector<double> least(4001, 0.0);  // each sample's least ns over the two passes, from the rows
    while (std::getline(in, line)) {
        std::vector<double> v;
        std::stringstream cells(line);
        for (std::string c; std::getline(cells, c, ',');) v.push_back(std::stod(c));
        REQUIRE(v.size() == 10);
        CHECK(v[0] == static_cast<double>(rows / 4001));  // pass
        CHECK(v[1] == static_cast<double>(rows % 4001));  // sample
        CHECK(v[2] > 0.0);                                // ns
        double& l = least[rows % 4001];
        l = rows < 4001 ? v[2] : std::min(l, v[2]);
        in_contact += v[3] == 1.0 ? 1 : 0;
        // The stages are parts of the profiled tick: their sum is at most its time.
        const double staged = v[4] + v[5] + v[6] + v[7] + v[8];
        CHECK(staged > 0.0);
        CHECK(staged <= v[9]);
        ++rows;
    }
    CHECK(rows == 2 * 4001);
    CHECK(in_contact == 2 * 4000);  // row 0 of each pass is the free-space start above the stroke
    // With two passes the tail is also given over each tick's least time across them (the code's
    // own tail): the same figures as the rows give, by nearest rank (tick times are whole ns).
    std::sort(least.begin(), least.end());
    const std::string least_line = "each tick's least over the 2 passes";
    const std::size_t at = t.out.find(least_line);
    REQUIRE(at != std::string::npos);
    double median = -1.0, p99 = -1.0, p999 = -1.0, max = -1.0;
    REQUIRE(std::sscanf(t.out.c_str() + t.out.find("median", at), "median %lf, p99 %lf, p99.9 %lf, max %lf", &median, &p99,
                        &p999, &max) == 4);
    CHECK(median == least[2000]);  // rank 4,001 / 2
    CHECK(p99 == least[3960]);     // rank 4,001 x 990 / 1,000
    CHECK(p999 == least[3996]);    // rank 4,001 x 999 / 1,000
    CHECK(max == least.back());
    // One pass has nothing to take the least over: the line is not printed.
    CHECK(b.out.find(least_line) == std::string::npos);

    // --ticks without a scene is refused, naming what it needs.
    const auto bad = run_contactlab({"bench", "--ticks", ticks_path});
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--ticks needs --scene") != std::string::npos);
}

TEST_CASE("generate peer-workload: a segment count below 1 is refused, naming the option") {
    TempDir dir;
    const auto p = run_contactlab({"generate", "peer-workload", "--segments", "0", "-o", dir.file("p.json"), "--trace",
                                   dir.file("p.csv")});
    CHECK(p.exit_code != 0);
    CHECK(p.err.find("--segments") != std::string::npos);
}
