// test_wearable_slope.cpp — the sim-wearable "device fault" found in the editor on the bumps,
// reproduced headless: a finger held 2 mm into a surface sloping down toward the fingertip by
// 26.6 degrees (steeper than the 25 degrees of roll the seed's platform reaches at rest). Each
// time the force ramped in from zero the light touch asked for a pose the cables cannot wrap and
// the device faulted ("a platform pose outside the workspace"), so the finger never got out of
// fault; the contact display now asks only for poses the platform can take.
#include "process.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <string>

using namespace cli_test;

TEST_CASE("sim-wearable held on a 26.6 degree down-slope: engaged, no device fault") {
    TempDir dir;
    const std::string scene_path = dir.file("slope.json");
    // Solid below a line falling 1 in 2 to the right: its normal is 26.6 degrees right of up.
    std::ofstream(scene_path) << R"({"version": 1, "finger": {"radius": 0.026, "length": 0.02},
        "force": {"model": "spring", "stiffness": 1000.0, "max_force": 1.5},
        "contours": [{"closed": false, "segments": [{"type": "line", "from": [-0.1, 0.05], "to": [0.1, -0.05]}]}]})";
    const double nx = 1.0 / std::sqrt(5.0), ny = 2.0 / std::sqrt(5.0);  // the surface's normal
    auto centre = [&](double depth) {  // finger centre (m) `depth` into the surface at the origin
        return std::to_string((0.026 - depth) * nx) + "," + std::to_string((0.026 - depth) * ny);
    };
    const std::string hand = dir.file("hand.csv");
    std::ofstream(hand) << "t,x,y,phi\n0," << centre(-0.01) << ",0\n0.5," << centre(0.002) << ",0\n3," << centre(0.002)
                        << ",0\n";
    const std::string out = dir.file("out.csv");
    const ProcessResult p = run_contactlab({"simulate", scene_path, "--device", "sim-wearable", "--hand", hand, "-o", out});
    INFO(p.err);
    REQUIRE(p.exit_code == 0);
    CHECK(contains(p.err, "state engaged, 0 fault(s)"));
    // Pressing 2 mm at 1000 N/m is 2 N, clamped to 1.5 N: the platform shows the slope.
    CHECK(contains(p.err, "max |F| 1.500 N"));
}
