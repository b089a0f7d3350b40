// haply_kinematics_cli.cpp — `contactlab haply-kinematics`: the Haply 2DIY's pantograph kinematics
// as a calibration diagnostic, in hAPI's frame and convention (drivers/usb/haply_kinematics.hpp).
//   --angles A1,A2    -> {"hardware": 3, "angles_deg": [...], "position_m": [x, y], "jacobian_m_per_rad": [[..],[..]]}
//   --position X,Y    -> the same, from the inverse kinematics
// Angles are the motor angles the board reports (deg, counter-clockwise from +x); positions are
// metres in the device frame (motor 1's axis at the origin, y toward the handle). The Jacobian
// J = dP/dt maps motor angle rates (rad/s) to handle velocity (m/s); J^T maps a handle force (N)
// to the motor torques (N m). Bad input (not two numbers, non-finite, unreachable, singular) exits 2.
#include "engine/app/subcommands.hpp"

#include "drivers/usb/haply_kinematics.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

namespace contactlab::app {

namespace {

namespace hk = drivers::haply;

// "a,b" as two finite numbers (std::from_chars: no locale; one leading '+' allowed).
std::array<double, 2> two_numbers(const std::string& s, const char* what, const char* unit) {
    const std::size_t comma = s.find(',');
    if (comma == std::string::npos || s.find(',', comma + 1) != std::string::npos)
        throw BadInput(std::string(what) + " wants two comma-separated numbers in " + unit + ", got '" + s + "'");
    const std::string f[2] = {s.substr(0, comma), s.substr(comma + 1)};
    std::array<double, 2> v{};
    for (int i = 0; i < 2; ++i) {
        const char* b = f[i].data();
        const char* end = b + f[i].size();
        if (b != end && *b == '+' && end - b > 1 && b[1] != '-' && b[1] != '+') ++b;
        const auto r = std::from_chars(b, end, v[i]);
        if (r.ec == std::errc::result_out_of_range)
            throw BadInput(std::string(what) + ": '" + f[i] + "' is beyond what a double holds");
        if (f[i].empty() || r.ec != std::errc() || r.ptr != end)
            throw BadInput(std::string(what) + " wants two comma-separated numbers in " + unit + ", got '" + s + "'");
        if (!std::isfinite(v[i])) throw BadInput(std::string(what) + ": '" + f[i] + "' is not a finite number");
    }
    return v;
}

int run(const std::string& angles, const std::string& position, int generation) {
    if (angles.empty() == position.empty())
        throw BadInput("haply-kinematics wants exactly one of --angles A1,A2 or --position X,Y");
    bool ok = false;
    const hk::HaplyHardware hw = hk::hardware(generation, &ok);
    if (!ok) throw BadInput("--hardware must be 2 or 3 (the 2DIY's board generation), got " + std::to_string(generation));
    std::array<double, 2> t{};  // rad
    hk::Vec p;                  // m
    if (!angles.empty()) {
        const auto a = two_numbers(angles, "--angles", "degrees");
        t = {a[0] * hk::kDegree, a[1] * hk::kDegree};
        const hk::KinStatus st = hk::forward_kinematics(hw.geometry, t, p);
        if (st == hk::KinStatus::singular)
            throw BadInput("--angles " + angles + ": the arms cannot be assembled at these angles: the elbows coincide "
                           "and the handle could be anywhere on a circle about them");
        if (st != hk::KinStatus::ok)
            throw BadInput("--angles " + angles + ": the arms cannot be assembled at these angles (" + hk::to_string(st) +
                           "): the elbows are more than 2 L = " + std::to_string(2.0 * hw.geometry.L) + " m apart");
    } else {
        const auto v = two_numbers(position, "--position", "metres");
        p = {v[0], v[1]};
        const hk::KinStatus st = hk::inverse_kinematics(hw.geometry, p, t);
        if (st != hk::KinStatus::ok)
            throw BadInput("--position " + position + " is out of the 2DIY's reach (" + hk::to_string(st) + ")");
    }
    hk::Mat2 J{};
    const hk::KinStatus js = hk::jacobian(hw.geometry, t, J);
    if (js != hk::KinStatus::ok)
        throw BadInput(std::string(angles.empty() ? "--position " + position : "--angles " + angles) +
                       " is at a singular pose of the pantograph (an arm stretched or folded, or the distal links "
                       "parallel): no Jacobian");
    nlohmann::json out;
    out["hardware"] = hw.generation;
    out["links_m"] = {{"l", hw.geometry.l}, {"L", hw.geometry.L}, {"d", hw.geometry.d}};
    out["angles_deg"] = {t[0] / hk::kDegree, t[1] / hk::kDegree};
    out["position_m"] = {p.x, p.y};
    out["jacobian_m_per_rad"] = {{J[0][0], J[0][1]}, {J[1][0], J[1][1]}};
    std::printf("%s\n", out.dump(2).c_str());
    return 0;
}

}  // namespace

void register_haply_kinematics_command(CLI::App& app, int& rc) {
    CLI::App* cmd = app.add_subcommand(
        "haply-kinematics",
        "Haply 2DIY pantograph kinematics for calibration (hAPI's frame, published link lengths): motor angles to "
        "handle position (m) and Jacobian, or a position to angles; JSON on stdout");
    auto angles = std::make_shared<std::string>();
    auto position = std::make_shared<std::string>();
    auto generation = std::make_shared<int>(3);
    cmd->add_option("--angles", *angles, "motor angles A1,A2 in degrees, as the board reports them");
    cmd->add_option("--position", *position, "a handle position X,Y in metres (device frame)");
    cmd->add_option("--hardware", *generation, "the 2DIY's board generation: 3 (current, d = 0.038 m) or 2 (d = 0)")
        ->default_val(3);
    cmd->callback([&rc, angles, position, generation] { rc = run(*angles, *position, *generation); });
}

}  // namespace contactlab::app
