// test_trace.cpp — `contactlab trace`: the numbers it writes, checked against the physics of a
// circular pad on a line (scenes/flat.json and a slanted floor written here), not against snapshots.
//
// Flat floor y = 0, pad radius R, finger centre at height y < R: the proxy rests on the floor at
// (x, R), the penetration is R - y, the spring pushes straight up with Ke (R - y) (clamped to the
// max force), and a finger tilted by phi touches at l = -R phi (DESIGN.md "Conventions").
#include "trace_fixture.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

using namespace cli_test;

namespace {

void check_echo(const std::vector<double>& row, const Sample& s) {
    CHECK(row[T] == s.t);
    CHECK(row[X] == s.x);
    CHECK(row[Y] == s.y);
    CHECK(row[PHI] == s.phi);
}

// Every row of a run over descend_and_tilt() on a flat floor at y = 0.
void check_flat_run(const TraceRun& r, const std::vector<Sample>& in, double R, double Ke, double max_force) {
    REQUIRE(r.proc.exit_code == 0);
    REQUIRE(r.output_exists);
    CHECK(r.csv.header == kOutputHeader);
    REQUIRE(r.csv.rows.size() == in.size());
    std::size_t contacts = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
        CAPTURE(i);
        const std::vector<double>& row = r.csv.rows[i];
        REQUIRE(row.size() == static_cast<std::size_t>(NCOLS));
        const Sample& s = in[i];
        check_echo(row, s);
        if (s.y > R) {  // the pad's lowest point is above the floor: free space
            CHECK(row[CONTACT] == 0.0);
            CHECK(row[DEPTH] == 0.0);
            CHECK(row[FX] == 0.0);
            CHECK(row[FY] == 0.0);
            CHECK(std::abs(row[PROXY_X] - s.x) <= 1e-12);  // the proxy tracks the finger
            CHECK(std::abs(row[PROXY_Y] - s.y) <= 1e-12);
            continue;
        }
        ++contacts;
        const double depth = R - s.y;
        const double f = std::min(Ke * depth, max_force);
        CHECK(row[CONTACT] == 1.0);
        CHECK(std::abs(row[PROXY_X] - s.x) <= kTol);  // frictionless floor: no sideways shift
        CHECK(std::abs(row[PROXY_Y] - R) <= kTol);    // resting on the floor
        CHECK(std::abs(row[DEPTH] - depth) <= kTol);
        CHECK(std::abs(row[FX]) <= kTol);             // normal force only
        CHECK(std::abs(row[FY] - f) <= kTol);
        CHECK(std::abs(row[L_D] - (-R * s.phi)) <= kTol);
        // Internal consistency: depth is the proxy-finger distance.
        CHECK(std::abs(row[DEPTH] - std::hypot(row[PROXY_X] - s.x, row[PROXY_Y] - s.y)) <= 1e-12);
    }
    CHECK(contacts == in.size() - 3);
    CHECK(contains(r.proc.err, std::to_string(in.size()) + " samples, " + std::to_string(contacts) + " in contact"));
}

// A straight floor through the origin at 45 degrees, solid below-left: free-side normal n = (1,1)/sqrt 2.
const char* kSlantedScene = R"({
  "version": 1,
  "description": "A floor at 45 degrees through the origin, solid below.",
  "finger": { "radius": 0.026, "length": 0.02 },
  "contours": [ { "closed": false, "segments": [
    { "type": "line", "from": [-0.2, 0.2], "to": [0.2, -0.2] } ] } ],
  "force": { "model": "spring", "stiffness": 1000.0, "max_force": 1.5 },
  "contact_location": { "rule": "centroid" }
}
)";

}  // namespace

TEST_CASE("trace on the flat floor: free space, then the spring force on the floor and l_d = -R phi") {
    TempDir dir;
    const auto in = descend_and_tilt(kFlatR, 0.001, flat_tilts());
    const TraceRun r = run_trace(dir, scene("flat.json"), samples_csv(in));
    INFO("stderr: " << r.proc.err);
    check_flat_run(r, in, kFlatR, kFlatKe, kFlatMaxF);
    // The numbers the brief states, spelled out: 1 mm into a 1000 N/m spring is 1 N, straight up.
    const auto& row = r.csv.rows[3];
    CHECK(std::abs(row[DEPTH] - 0.001) <= kTol);
    CHECK(std::abs(row[FY] - 1.0) <= kTol);
    CHECK(std::abs(row[PROXY_Y] - 0.026) <= kTol);
    CHECK(r.proc.out.empty());  // the report goes to stderr; stdout stays clean
    CHECK(dir.entries() == std::vector<std::string>{"in.csv", "out.csv"});  // no temporary left behind
}

TEST_CASE("trace --stiffness 500 halves the force and keeps the geometry") {
    TempDir dir;
    const auto in = descend_and_tilt(kFlatR, 0.001, flat_tilts());
    const TraceRun base = run_trace(dir, scene("flat.json"), samples_csv(in));
    const TraceRun soft = run_trace(dir, scene("flat.json"), samples_csv(in), {"--stiffness", "500"});
    INFO("stderr: " << soft.proc.err);
    check_flat_run(soft, in, kFlatR, 500.0, kFlatMaxF);
    REQUIRE(base.csv.rows.size() == soft.csv.rows.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        CAPTURE(i);
        CHECK(std::abs(soft.csv.rows[i][FY] - 0.5 * base.csv.rows[i][FY]) <= 1e-12);
        CHECK(soft.csv.rows[i][PROXY_Y] == base.csv.rows[i][PROXY_Y]);
        CHECK(soft.csv.rows[i][DEPTH] == base.csv.rows[i][DEPTH]);
    }
    CHECK(std::abs(soft.csv.rows[3][FY] - 0.5) <= kTol);
}

TEST_CASE("trace --max-force 0.2 clamps |F| on the flat floor and the proxy does not move") {
    TempDir dir;
    const auto in = descend_and_tilt(kFlatR, 0.001, flat_tilts());
    const TraceRun r = run_trace(dir, scene("flat.json"), samples_csv(in), {"--max-force", "0.2"});
    INFO("stderr: " << r.proc.err);
    check_flat_run(r, in, kFlatR, kFlatKe, 0.2);  // 1 N unclamped -> 0.2 N, still straight up
    for (std::size_t i = 3; i < in.size(); ++i) {
        CAPTURE(i);
        CHECK(std::abs(std::hypot(r.csv.rows[i][FX], r.csv.rows[i][FY]) - 0.2) <= kTol);
        CHECK(std::abs(r.csv.rows[i][DEPTH] - 0.001) <= kTol);  // clamping the force leaves the depth
    }
}

TEST_CASE("trace --max-force keeps the force direction on a slanted floor") {
    TempDir dir;
    write_text(dir.file("slanted.json"), kSlantedScene);
    const double R = kFlatR;
    const double c = std::sqrt(0.5);  // n = (c, c)
    const double phi0 = -0.25 * std::numbers::pi;  // the pad's middle, at phi - pi/2, faces -n
    const std::vector<double> tilts = {0.0, 0.2, -0.3};
    std::vector<Sample> in;
    in.push_back({0.0, (R + 0.02) * c, (R + 0.02) * c, phi0});  // 2 cm off the floor
    double t = 0.001;
    for (double d : tilts) {
        in.push_back({t, (R - 0.001) * c, (R - 0.001) * c, phi0 + d});  // 1 mm in along -n
        t += 0.001;
    }
    for (const double max_force : {1.5, 0.2}) {
        CAPTURE(max_force);
        const TraceRun r = run_trace(dir, dir.file("slanted.json"), samples_csv(in),
                                     {"--max-force", g17(max_force)});
        INFO("stderr: " << r.proc.err);
        REQUIRE(r.proc.exit_code == 0);
        REQUIRE(r.csv.rows.size() == in.size());
        const auto& free_row = r.csv.rows[0];
        CHECK(free_row[CONTACT] == 0.0);
        CHECK(free_row[FX] == 0.0);
        CHECK(free_row[FY] == 0.0);
        const double f = std::min(kFlatKe * 0.001, max_force);  // 1 N, or the clamp
        for (std::size_t i = 1; i < in.size(); ++i) {
            CAPTURE(i);
            const auto& row = r.csv.rows[i];
            check_echo(row, in[i]);
            CHECK(row[CONTACT] == 1.0);
            CHECK(std::abs(row[PROXY_X] - R * c) <= kTol);  // on the c-space line, R off the floor
            CHECK(std::abs(row[PROXY_Y] - R * c) <= kTol);
            CHECK(std::abs(row[DEPTH] - 0.001) <= kTol);
            CHECK(std::abs(row[FX] - f * c) <= kTol);  // along n: direction kept under the clamp
            CHECK(std::abs(row[FY] - f * c) <= kTol);
            CHECK(std::abs(row[L_D] - (-R * tilts[i - 1])) <= kTol);
        }
    }
}

TEST_CASE("trace --radius 0.03 --length 0.02 rests the proxy at y = 0.03") {
    TempDir dir;
    const double R = 0.03;
    const auto in = descend_and_tilt(R, 0.001, {0.1, -0.2, 0.3});  // |0.03 * 0.3| < 0.01
    const TraceRun r = run_trace(dir, scene("flat.json"), samples_csv(in), {"--radius", "0.03", "--length", "0.02"});
    INFO("stderr: " << r.proc.err);
    check_flat_run(r, in, R, kFlatKe, kFlatMaxF);
    CHECK(std::abs(r.csv.rows[3][PROXY_Y] - 0.03) <= kTol);

    // The same finger heights with the scene's R = 0.026: y = 0.029 > 0.026, the pad never touches.
    const TraceRun base = run_trace(dir, scene("flat.json"), samples_csv(in));
    REQUIRE(base.proc.exit_code == 0);
    REQUIRE(base.csv.rows.size() == in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        CAPTURE(i);
        CHECK(base.csv.rows[i][CONTACT] == 0.0);
        CHECK(base.csv.rows[i][FY] == 0.0);
    }
}

TEST_CASE("trace output numbers round-trip at full precision") {
    TempDir dir;
    // Values whose shortest text needs all 17 digits, or whose %.6g/%.15g text reads back differently.
    const std::string input =
        "t,x,y,phi\n"
        "0.1,0.30000000000000004,0.1,0.1\n"
        "0.30000000000000004,0.33333333333333331,0.050000000000000003,-0.29999999999999999\n"
        "0.33333333333333331,-0.066666666666666666,0.12345678901234568,3.1415926535897931\n"
        "0.7,1.0000000000000002,0.99999999999999989,1e-300\n"
        "12345.678901234567,-1e-07,0.05,2.2250738585072014e-308\n";
    const TraceRun r = run_trace(dir, scene("flat.json"), input);
    INFO("stderr: " << r.proc.err);
    REQUIRE(r.proc.exit_code == 0);
    REQUIRE(r.csv.rows.size() == 5);
    const std::vector<Sample> expected = {
        {0.1, 0.1 + 0.2, 0.1, 0.1},
        {0.1 + 0.2, 1.0 / 3.0, 0.05, -0.3},
        {1.0 / 3.0, -0.066666666666666666, 0.12345678901234568, std::numbers::pi},
        {0.7, 1.0000000000000002, 0.99999999999999989, 1e-300},
        {12345.678901234567, -1e-7, 0.05, 2.2250738585072014e-308},
    };
    CHECK(0.1 + 0.2 != 0.3);  // the point of the first value
    for (std::size_t i = 0; i < expected.size(); ++i) {
        CAPTURE(i);
        check_echo(r.csv.rows[i], expected[i]);
        CHECK(r.csv.rows[i][CONTACT] == 0.0);  // all well above the floor
    }
    CHECK(r.csv.raw[0][X] == "0.30000000000000004");
}

TEST_CASE("trace reads Windows line ends and a header with spaces the same way") {
    TempDir dir;
    const auto in = descend_and_tilt(kFlatR, 0.001, flat_tilts());
    const TraceRun lf = run_trace(dir, scene("flat.json"), samples_csv(in));
    const std::string lf_out = read_text(dir.file("out.csv"));
    const TraceRun crlf = run_trace(dir, scene("flat.json"), samples_csv(in, "\r\n"));
    INFO("stderr: " << crlf.proc.err);
    REQUIRE(crlf.proc.exit_code == 0);
    CHECK(read_text(dir.file("out.csv")) == lf_out);

    std::string spaced = samples_csv(in);
    spaced.replace(0, spaced.find('\n'), "t, x, y, phi");
    const TraceRun sp = run_trace(dir, scene("flat.json"), spaced);
    REQUIRE(sp.proc.exit_code == 0);
    CHECK(read_text(dir.file("out.csv")) == lf_out);
}

TEST_CASE("trace with a header and no samples writes a header and no rows") {
    TempDir dir;
    const TraceRun r = run_trace(dir, scene("flat.json"), "t,x,y,phi\n");
    INFO("stderr: " << r.proc.err);
    REQUIRE(r.proc.exit_code == 0);
    CHECK(r.csv.header == kOutputHeader);
    CHECK(r.csv.rows.empty());
}

TEST_CASE("trace --force-model ellipsoid with eccentricity 1 is the spring of the same total stiffness") {
    TempDir dir;
    const auto in = descend_and_tilt(kFlatR, 0.001, flat_tilts());
    const TraceRun spring = run_trace(dir, scene("flat.json"), samples_csv(in));
    const TraceRun ell = run_trace(dir, scene("flat.json"), samples_csv(in),
                                   {"--force-model", "ellipsoid", "--eccentricity", "1", "--total-stiffness", "1000"});
    INFO("stderr: " << ell.proc.err);
    REQUIRE(ell.proc.exit_code == 0);
    REQUIRE(ell.csv.rows.size() == spring.csv.rows.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        CAPTURE(i);
        CHECK(std::abs(ell.csv.rows[i][FX] - spring.csv.rows[i][FX]) <= 1e-12);
        CHECK(std::abs(ell.csv.rows[i][FY] - spring.csv.rows[i][FY]) <= 1e-12);
    }
}

TEST_CASE("trace --friction holds the stiction point: sideways motion inside the cone pulls back") {
    // Press 1 mm into the flat floor at x = 0.01, then slide 0.4 mm right: inside the cone
    // (mu 0.5 * 1 mm = 0.5 mm), the stiction columns stay at x = 0.01 and fx = -Ke * 0.4 mm
    // (|F| = 1.08 N, under the scene's 1.5 N clamp).
    TempDir dir;
    const std::vector<Sample> in = {{0.000, 0.01, kFlatR + 0.02, 0.0},
                                    {0.001, 0.01, kFlatR - 0.001, 0.0},
                                    {0.002, 0.0104, kFlatR - 0.001, 0.0}};
    const TraceRun r = run_trace(dir, scene("flat.json"), samples_csv(in), {"--friction", "0.5"});
    INFO("stderr: " << r.proc.err);
    REQUIRE(r.proc.exit_code == 0);
    REQUIRE(r.csv.rows.size() == 3);
    CHECK(r.csv.rows[0][STICTION_X] == in[0].x);  // free space: the anchor is the finger itself
    CHECK(std::abs(r.csv.rows[2][STICTION_X] - 0.01) <= kTol);
    CHECK(std::abs(r.csv.rows[2][STICTION_Y] - kFlatR) <= kTol);
    CHECK(std::abs(r.csv.rows[2][FX] - (-kFlatKe * 0.0004)) <= 1e-9);
    CHECK(std::abs(r.csv.rows[2][FY] - kFlatKe * 0.001) <= 1e-9);
}

TEST_CASE("trace rejects absurd force-law options with exit 2 naming them") {
    TempDir dir;
    const auto in = descend_and_tilt(kFlatR, 0.001, flat_tilts());
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{"--force-model", "magnet"}, {"--friction", "-1"}, {"--friction", "0.2", "--friction-dynamic", "0.5"},
          {"--damping", "1e9"}, {"--eccentricity", "0.5"}, {"--force-model", "ellipsoid", "--k-normal", "0"},
          {"--contact-force", "max"}}) {
        const TraceRun r = run_trace(dir, scene("flat.json"), samples_csv(in), extra);
        CAPTURE(extra[0]);
        CHECK(r.proc.exit_code == 2);
        CHECK(r.proc.err.find(extra[0]) != std::string::npos);
        CHECK_FALSE(r.output_exists);
    }
}

TEST_CASE("trace: a first sample with the pad inside the floor is said, with its time and depth, and the output is unchanged") {
    TempDir dir;
    // Pad bottom 1.5 mm below the floor from the start, then up and out, then down 1 mm onto it.
    const double R = kFlatR;
    const std::vector<Sample> in = {{0.25, 0.0, R - 0.0015, 0.0}, {0.251, 0.0, R + 0.002, 0.0}, {0.252, 0.0, R - 0.001, 0.0}};
    const TraceRun r = run_trace(dir, scene("flat.json"), samples_csv(in));
    REQUIRE(r.proc.exit_code == 0);
    CHECK(r.proc.err.find("trace: warning: the first hand sample (t = 0.25 s") != std::string::npos);
    CHECK(r.proc.err.find("1.500 mm inside a solid") != std::string::npos);
    REQUIRE(r.csv.rows.size() == 3);
    CHECK(r.csv.rows[0][CONTACT] == 0.0);  // no history: the proxy starts at the hand
    CHECK(r.csv.rows[2][CONTACT] == 1.0);  // came from above: the floor is felt, 1 mm deep
    CHECK(std::abs(r.csv.rows[2][DEPTH] - 0.001) <= kTol);

    const std::vector<Sample> clear = {{0.0, 0.0, R + 0.001, 0.0}, {0.001, 0.0, R - 0.001, 0.0}};
    const TraceRun quiet = run_trace(dir, scene("flat.json"), samples_csv(clear));
    REQUIRE(quiet.proc.exit_code == 0);
    CHECK(quiet.proc.err.find("warning") == std::string::npos);
}
