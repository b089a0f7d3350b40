// test_haply_kinematics.cpp — `contactlab haply-kinematics`: the 2DIY's pantograph from the
// command line: the symmetric pose on the axis between the motors, position -> angles -> position
// round trips, J against a finite difference of two runs, and bad input exiting 2.
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <string>

using namespace cli_test;

namespace {

nlohmann::json run_json(const std::vector<std::string>& args) {
    const ProcessResult r = run_contactlab(args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out);
}

std::string num(double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

}  // namespace

TEST_CASE("haply-kinematics: symmetric angles put the handle midway between the motors") {
    // Generation 3: motors 0.038 m apart; arms at 180 - a and a degrees are mirror images.
    const auto j = run_json({"haply-kinematics", "--angles", "120,60"});
    CHECK(j.at("hardware") == 3);
    CHECK(j.at("links_m").at("d").get<double>() == 0.038);
    const double x = j.at("position_m")[0], y = j.at("position_m")[1];
    // Elbows at (0.07 cos 120, 0.07 sin 120) and (0.038 + 0.07 cos 60, 0.07 sin 60): 0.108 m
    // apart, so the handle is sqrt(0.09^2 - 0.054^2) = 0.072 m beyond their line.
    CHECK(x == doctest::Approx(0.019).epsilon(1e-12));
    CHECK(y == doctest::Approx(0.07 * std::sin(60.0 * 3.14159265358979323846 / 180.0) + 0.072).epsilon(1e-12));
    // Mirror symmetry about x = d/2 takes t1 to pi - t2: turning motor 1 counter-clockwise mirrors
    // turning motor 2 clockwise, so dx/dt1 = dx/dt2 and dy/dt1 = -dy/dt2.
    const auto& J = j.at("jacobian_m_per_rad");
    CHECK(J[0][0].get<double>() == doctest::Approx(J[0][1].get<double>()).epsilon(1e-12));
    CHECK(J[1][0].get<double>() == doctest::Approx(-J[1][1].get<double>()).epsilon(1e-12));
    CHECK(std::abs(J[0][0].get<double>()) > 0.01);  // m/rad: not a degenerate pose
}

TEST_CASE("haply-kinematics: --position and --angles invert each other, on both generations") {
    for (const char* hw : {"2", "3"}) {
        for (const char* pos : {"0.0,0.08", "0.05,0.1", "-0.03,0.05"}) {
            const auto a = run_json({"haply-kinematics", "--hardware", hw, "--position", pos});
            const std::string angles = num(a.at("angles_deg")[0]) + "," + num(a.at("angles_deg")[1]);
            const auto b = run_json({"haply-kinematics", "--hardware", hw, "--angles", angles});
            CHECK(std::abs(b.at("position_m")[0].get<double>() - a.at("position_m")[0].get<double>()) < 1e-12);
            CHECK(std::abs(b.at("position_m")[1].get<double>() - a.at("position_m")[1].get<double>()) < 1e-12);
        }
    }
}

TEST_CASE("haply-kinematics: the printed Jacobian is the derivative of the printed position") {
    // One motor turned by 1e-4 deg: the position moves by J's column times that, to second order
    // (|P''| ~ 0.2 m/rad^2 x (1.7e-6 rad)^2 ~ 6e-13 m), well within the 1e-10 m asserted.
    const auto a = run_json({"haply-kinematics", "--angles", "140,30"});
    const auto b = run_json({"haply-kinematics", "--angles", "140.0001,30"});
    const double dt = 1e-4 * 3.14159265358979323846 / 180.0;  // rad
    const auto& J = a.at("jacobian_m_per_rad");
    CHECK(std::abs(b.at("position_m")[0].get<double>() - a.at("position_m")[0].get<double>() - J[0][0].get<double>() * dt) < 1e-10);
    CHECK(std::abs(b.at("position_m")[1].get<double>() - a.at("position_m")[1].get<double>() - J[1][0].get<double>() * dt) < 1e-10);
}

TEST_CASE("haply-kinematics: bad input names what and exits 2") {
    struct Case {
        std::vector<std::string> args;
        const char* says;
    };
    const Case cases[] = {
        {{"haply-kinematics"}, "exactly one of --angles A1,A2 or --position X,Y"},
        {{"haply-kinematics", "--angles", "1,2", "--position", "0,0.1"}, "exactly one of"},
        {{"haply-kinematics", "--angles", "120"}, "--angles wants two comma-separated numbers in degrees"},
        {{"haply-kinematics", "--angles", "120,60,3"}, "--angles wants two"},
        {{"haply-kinematics", "--angles", "abc,60"}, "--angles wants two"},
        {{"haply-kinematics", "--angles", "nan,60"}, "is not a finite number"},
        {{"haply-kinematics", "--position", "0,0.3"}, "--position 0,0.3 is out of the 2DIY's reach"},
        {{"haply-kinematics", "--position", "0,1e999"}, "beyond what a double holds"},
        {{"haply-kinematics", "--hardware", "2", "--angles", "90,90"}, "the elbows coincide"},
        {{"haply-kinematics", "--hardware", "4", "--angles", "120,60"}, "--hardware must be 2 or 3"},
    };
    for (const Case& c : cases) {
        const ProcessResult r = run_contactlab(c.args);
        INFO(c.args.back() << ": " << r.err);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, c.says));
    }
}
