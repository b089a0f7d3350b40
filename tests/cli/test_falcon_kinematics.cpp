// test_falcon_kinematics.cpp — `contactlab falcon-kinematics`: the published Falcon model's encoder
// map (35 deg at count 0, 360/9880.7 deg per count), equal angles on the device axis, and the
// position -> encoders -> position round trip within one count's resolution; bad input exits 2.
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace cli_test;

namespace {

// 4 x 320 encoder slots x 110 mm arm drum / 14.25 mm motor shaft.
constexpr double kCountsPerRev = 4.0 * 320.0 * 110.0 / 14.25;
constexpr double kPi = 3.14159265358979323846;

nlohmann::json run_json(const std::vector<std::string>& args) {
    const ProcessResult r = run_contactlab(args);
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out);
}

}  // namespace

TEST_CASE("falcon-kinematics: 35 degrees at zero counts for each arm, and the grip on the device axis") {
    const auto j = run_json({"falcon-kinematics", "--encoders", "0,0,0"});
    REQUIRE(j["theta_deg"].size() == 3);
    for (int i = 0; i < 3; ++i) CHECK(j["theta_deg"][i].get<double>() == doctest::Approx(35.0).epsilon(1e-12));
    REQUIRE(j["position_m"].size() == 3);
    CHECK(std::fabs(j["position_m"][0].get<double>()) < 1e-9);
    CHECK(std::fabs(j["position_m"][1].get<double>()) < 1e-9);
    CHECK(j["position_m"][2].get<double>() > 0.07);  // m, out along the axis toward the user
    CHECK(j["position_m"][2].get<double>() < 0.18);
}

TEST_CASE("falcon-kinematics: each count turns its arm by 360/9880.7 degrees") {
    const auto j = run_json({"falcon-kinematics", "--encoders=400,-700,100"});
    const int e[3] = {400, -700, 100};
    for (int i = 0; i < 3; ++i)
        CHECK(j["theta_deg"][i].get<double>() == doctest::Approx(35.0 + e[i] * 360.0 / kCountsPerRev).epsilon(1e-12));
    CHECK(j["encoders"] == nlohmann::json({400, -700, 100}));
}

TEST_CASE("falcon-kinematics: position to encoders and back lands within one count's resolution") {
    for (const char* pos : {"0.01,-0.02,0.12", "-0.03,0.025,0.1", "0,0,0.14"}) {
        CAPTURE(pos);
        const auto inv = run_json({"falcon-kinematics", "--position", pos});
        const auto enc = inv["encoders"];
        REQUIRE(enc.size() == 3);
        for (int i = 0; i < 3; ++i) {
            // The counts are the angle's, rounded: within half a count.
            const double exact = (inv["theta_deg"][i].get<double>() - 35.0) * kCountsPerRev / 360.0;
            CHECK(std::fabs(exact - enc[i].get<double>()) <= 0.5);
        }
        const std::string counts = std::to_string(enc[0].get<int>()) + "," + std::to_string(enc[1].get<int>()) + "," +
                                   std::to_string(enc[2].get<int>());
        const auto fwd = run_json({"falcon-kinematics", "--encoders=" + counts});
        // Half a count is 0.32 mrad per arm; the Falcon's arms move the grip at most about
        // 0.2 m per rad, so three arms' rounding moves it well under 0.2 mm.
        const double half_count = 0.5 * 2.0 * kPi / kCountsPerRev;
        double err2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double d = fwd["position_m"][k].get<double>() - inv["position_m"][k].get<double>();
            err2 += d * d;
        }
        CHECK(std::sqrt(err2) < 3.0 * 0.2 * half_count);
    }
}

TEST_CASE("falcon-kinematics: not three integers, non-finite numbers, or an unreachable position exit 2") {
    struct Case {
        std::vector<std::string> args;
        const char* says;
    };
    const Case cases[] = {
        {{"falcon-kinematics", "--encoders", "1,2"}, "three"},
        {{"falcon-kinematics", "--encoders", "1,x,3"}, "integers"},
        {{"falcon-kinematics", "--encoders", "1.5,2,3"}, "integers"},
        {{"falcon-kinematics", "--encoders", "1,2,3,4"}, "three"},
        {{"falcon-kinematics", "--encoders", "40000,0,0"}, "16-bit"},
        {{"falcon-kinematics", "--position", "nan,0,0.1"}, "finite"},
        {{"falcon-kinematics", "--position", "0,inf,0.1"}, "finite"},
        {{"falcon-kinematics", "--position", "0,0,0.5"}, "reach"},
        {{"falcon-kinematics"}, "exactly one"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args.back());
        const ProcessResult r = run_contactlab(c.args);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, c.says));
        CHECK(r.out.empty());
    }
}
