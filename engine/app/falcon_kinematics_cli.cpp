// falcon_kinematics_cli.cpp — `contactlab falcon-kinematics`: the Falcon's kinematics as a
// calibration diagnostic, in the published model's frame and convention (falcon_kinematics.hpp).
//   --encoders E1,E2,E3  -> {"encoders": [...], "theta_deg": [...], "position_m": [x, y, z]}
//   --position X,Y,Z     -> {"position_m": [...], "theta_deg": [...], "encoders": [...]}
// theta_deg are the driven thigh angles (35 deg at count 0, 360/9880.7 deg per count); positions
// are metres in the device frame (x right, y up, z out of the device toward the user).
// Bad input (not three integers / numbers, non-finite, unreachable, no solution) exits 2.
#include "engine/app/subcommands.hpp"

#include "drivers/usb/falcon_kinematics.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

namespace contactlab::app {

namespace {

namespace fk = drivers::falcon;

// Splits "a,b,c" into exactly three non-empty fields.
std::array<std::string, 3> three_fields(const std::string& s, const char* what) {
    std::array<std::string, 3> out;
    std::size_t start = 0;
    for (int i = 0; i < 3; ++i) {
        const std::size_t comma = s.find(',', start);
        if ((i < 2) != (comma != std::string::npos))
            throw BadInput(std::string(what) + " wants three comma-separated values, got '" + s + "'");
        out[i] = s.substr(start, i < 2 ? comma - start : std::string::npos);
        if (out[i].empty()) throw BadInput(std::string(what) + " wants three comma-separated values, got '" + s + "'");
        start = comma + 1;
    }
    return out;
}

std::array<int, 3> parse_encoders(const std::string& s) {
    std::array<int, 3> e{};
    const auto f = three_fields(s, "--encoders");
    for (int i = 0; i < 3; ++i) {
        long v = 0;
        const char* b = f[i].data();
        const char* end = b + f[i].size();
        const auto r = std::from_chars(b, end, v);
        if (r.ec != std::errc() || r.ptr != end)
            throw BadInput("--encoders wants three integers (encoder counts), got '" + f[i] + "'");
        if (v < std::numeric_limits<std::int16_t>::min() || v > std::numeric_limits<std::int16_t>::max())
            throw BadInput("--encoders: " + f[i] + " is outside the Falcon's 16-bit encoder range [-32768, 32767]");
        e[i] = static_cast<int>(v);
    }
    return e;
}

// A number as given, whole: std::from_chars (no locale, subnormals such as 5e-324 read as the
// values they are), with one leading '+' allowed; anything else in the field is refused.
fk::Vec3 parse_position(const std::string& s) {
    const auto f = three_fields(s, "--position");
    double v[3];
    for (int i = 0; i < 3; ++i) {
        const char* b = f[i].data();
        const char* end = b + f[i].size();
        if (b != end && *b == '+' && end - b > 1 && b[1] != '-' && b[1] != '+') ++b;
        const auto r = std::from_chars(b, end, v[i]);
        if (r.ec == std::errc::result_out_of_range)
            throw BadInput("--position: '" + f[i] + "' is beyond what a double holds");
        if (r.ec != std::errc() || r.ptr != end) throw BadInput("--position wants three numbers in metres, got '" + f[i] + "'");
        if (!std::isfinite(v[i])) throw BadInput("--position: '" + f[i] + "' is not a finite number");
    }
    return {v[0], v[1], v[2]};
}

// The grip position `--encoders` prints for these counts: forward kinematics from the device's
// axis in the middle of the workspace (no earlier pose to start from). One function for both
// directions, so every position `--position` answers is read back by `--encoders`.
fk::KinStatus position_of_counts(const fk::FalconKinematics& kin, const std::array<int, 3>& e, std::array<double, 3>& th,
                                 fk::Vec3& p) {
    for (int i = 0; i < 3; ++i) th[i] = kin.theta_of(i, e[i]);
    return fk::forward_kinematics(kin.geometry(), th, fk::Vec3{0.0, 0.0, 0.11}, p);
}

int run(const std::string& encoders, const std::string& position) {
    if (encoders.empty() == position.empty())
        throw BadInput("falcon-kinematics wants exactly one of --encoders E1,E2,E3 or --position X,Y,Z");
    const fk::FalconKinematics kin;
    nlohmann::json out;
    if (!encoders.empty()) {
        const auto e = parse_encoders(encoders);
        std::array<double, 3> th{};
        fk::Vec3 p;
        const fk::KinStatus st = position_of_counts(kin, e, th, p);
        if (st != fk::KinStatus::ok)
            throw BadInput(std::string("--encoders: no grip position for these arm angles (") + fk::to_string(st) + ")");
        out["encoders"] = e;
        out["theta_deg"] = {th[0] / fk::kDegree, th[1] / fk::kDegree, th[2] / fk::kDegree};
        out["position_m"] = {p.x, p.y, p.z};
    } else {
        const fk::Vec3 p = parse_position(position);
        std::array<double, 3> th{};
        if (fk::inverse_kinematics(kin.geometry(), p, th) != fk::KinStatus::ok)
            throw BadInput("--position: " + position + " is out of the Falcon's reach (no leg angles put the grip there)");
        std::array<int, 3> counts{};
        for (int i = 0; i < 3; ++i) {
            const double c = std::round(kin.counts_exact(i, th[i]));
            if (!(c >= -32768.0 && c <= 32767.0))
                throw BadInput("--position: " + position + " needs encoder counts outside the 16-bit range");
            counts[i] = static_cast<int>(c);
        }
        // The counts must name this position again (what `--encoders` prints): near a singular
        // pose of the arms, at the workspace's edge, the rounded counts' arm angles have no grip
        // position the forward kinematics can find, or one far from this. Refused there.
        std::array<double, 3> rounded{};
        fk::Vec3 back;
        const fk::KinStatus st = position_of_counts(kin, counts, rounded, back);
        if (st != fk::KinStatus::ok)
            throw BadInput("--position: " + position + " is at the edge of the Falcon's workspace: the arms are near a "
                           "singular pose, and its encoder counts name no position (" + fk::to_string(st) + ")");
        // One count turns an arm by 2 pi / 9880.7 rad; a position within reach moves by at most
        // |J| times that per count. Twice the largest column of J at p bounds the round trip.
        fk::Mat3 J{};
        if (fk::jacobian(kin.geometry(), p, J) != fk::KinStatus::ok)
            throw BadInput("--position: " + position + " is at a singular pose of the Falcon's arms");
        double per_count = 0.0;  // m
        for (int c = 0; c < 3; ++c)
            per_count += std::hypot(J[0][c], J[1][c], J[2][c]) * (kin.theta_of(c, 1) - kin.theta_of(c, 0));
        const double moved = std::hypot(back.x - p.x, back.y - p.y, back.z - p.z);
        if (!(moved <= per_count))
            throw BadInput("--position: " + position + " is at the edge of the Falcon's workspace: its encoder counts "
                           "name a position " + std::to_string(moved * 1e3) + " mm away");
        out["position_m"] = {p.x, p.y, p.z};
        out["theta_deg"] = {th[0] / fk::kDegree, th[1] / fk::kDegree, th[2] / fk::kDegree};
        out["encoders"] = counts;
    }
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
}

}  // namespace

void register_falcon_kinematics_command(CLI::App& app, int& rc) {
    CLI::App* cmd = app.add_subcommand(
        "falcon-kinematics",
        "Novint Falcon kinematics for calibration (Stamper's model, published constants): encoder counts to "
        "arm angles and grip position (m), or a position to angles and counts; JSON on stdout");
    auto encoders = std::make_shared<std::string>();
    auto position = std::make_shared<std::string>();
    cmd->add_option("--encoders", *encoders, "three encoder counts E1,E2,E3 (arms top, right, lower left)");
    cmd->add_option("--position", *position, "a grip position X,Y,Z in metres (device frame)");
    cmd->callback([&rc, encoders, position] { rc = run(*encoders, *position); });
}

}  // namespace contactlab::app
