// test_falcon_kinematics.cpp — `contactlab falcon-kinematics`: the published Falcon model's encoder
// map (35 deg at count 0, 360/9880.7 deg per count), equal angles on the device axis, and the
// position -> encoders -> position round trip within one count's resolution; bad input exits 2.
#include "process.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

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

TEST_CASE("falcon-kinematics: a subnormal or a leading '+' is a number like any other") {
    // 5e-324 (the least subnormal) was "not three numbers" while 1e-300 was read.
    const auto a = run_json({"falcon-kinematics", "--position", "5e-324,+0,0.12"});
    CHECK(a["position_m"][0].get<double>() == 5e-324);
    const auto b = run_json({"falcon-kinematics", "--position", "0,0,0.12"});
    CHECK(a["encoders"] == b["encoders"]);
}

TEST_CASE("falcon-kinematics: every position it answers round-trips through --encoders, on a grid past the workspace") {
    // A 3 cm grid from 12 cm either side and 15 cm behind the base to 24 cm out: each position is
    // answered with counts that --encoders turns back into it (within the counts' resolution), or
    // refused with exit 2; never counts that --encoders cannot read back.
    int answered = 0, refused = 0;
    for (double x = -0.12; x <= 0.1201; x += 0.06)
        for (double y = -0.12; y <= 0.1201; y += 0.06)
            for (double z = -0.15; z <= 0.2401; z += 0.03) {
                char pos[96];
                std::snprintf(pos, sizeof pos, "%.17g,%.17g,%.17g", x, y, z);
                CAPTURE(pos);
                const ProcessResult r = run_contactlab({"falcon-kinematics", "--position", pos});
                if (r.exit_code == 2) {
                    ++refused;
                    if (z <= 0.0) CHECK(contains(r.err, "reach"));
                    continue;
                }
                REQUIRE(r.exit_code == 0);
                ++answered;
                const auto inv = nlohmann::json::parse(r.out);
                for (int i = 0; i < 3; ++i) CHECK(inv["theta_deg"][i].get<double>() > -90.0);
                const std::string counts = std::to_string(inv["encoders"][0].get<int>()) + "," +
                                           std::to_string(inv["encoders"][1].get<int>()) + "," +
                                           std::to_string(inv["encoders"][2].get<int>());
                const ProcessResult f = run_contactlab({"falcon-kinematics", "--encoders=" + counts});
                REQUIRE(f.exit_code == 0);
                const auto fwd = nlohmann::json::parse(f.out);
                double err2 = 0.0;
                for (int k = 0; k < 3; ++k) {
                    const double d = fwd["position_m"][k].get<double>() - inv["position_m"][k].get<double>();
                    err2 += d * d;
                }
                CHECK(std::sqrt(err2) < 1e-3);  // m: a few counts' worth at the very edge, well under 1 mm
            }
    // The grid holds both: the workspace's middle is answered, behind the base is refused.
    CHECK(answered >= 10);
    CHECK(refused >= 100);
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
        // Named regression cases (issue: a hostile user's inputs). Behind the base: the legs'
        // mirror solution through it (arm angles of -189 deg) was printed with exit 0.
        {{"falcon-kinematics", "--position", "0,0,-0.11"}, "reach"},
        {{"falcon-kinematics", "--position", "0.1,0,0"}, "reach"},
        // At the workspace's edge its counts named no position: `--encoders` called them singular.
        {{"falcon-kinematics", "--position", "0.1,0,0.11"}, "edge of the Falcon's workspace"},
        {{"falcon-kinematics", "--position", "1e400,0,0.1"}, "beyond what a double holds"},
        {{"falcon-kinematics", "--position", "0x1p3,0,0.1"}, "three numbers"},
        {{"falcon-kinematics", "--position", " 0,0,0.1"}, "three numbers"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.args.back());
        const ProcessResult r = run_contactlab(c.args);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, c.says));
        CHECK(r.out.empty());
    }
}
