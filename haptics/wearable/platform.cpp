// platform.cpp — rotation, the Euler-rate map and the assembly check (see platform.hpp).
#include "haptics/wearable/platform.hpp"

#include "haptics/wearable/kinematics.hpp"

#include <cmath>

namespace contactlab::wearable {

Eigen::Matrix3d rotation(const Pose& xi) {
    using Eigen::AngleAxisd;
    return (AngleAxisd(xi(5), Vec3::UnitZ()) * AngleAxisd(xi(4), Vec3::UnitY()) *
            AngleAxisd(xi(3), Vec3::UnitX()))
        .toRotationMatrix();
}

Mat6 euler_rate_map(const Pose& xi) {
    using Eigen::AngleAxisd;
    const Eigen::Matrix3d rz = AngleAxisd(xi(5), Vec3::UnitZ()).toRotationMatrix();
    const Eigen::Matrix3d ry = AngleAxisd(xi(4), Vec3::UnitY()).toRotationMatrix();
    Mat6 t = Mat6::Identity();
    t.block<3, 1>(3, 3) = rz * ry * Vec3::UnitX();
    t.block<3, 1>(3, 4) = rz * Vec3::UnitY();
    t.block<3, 1>(3, 5) = Vec3::UnitZ();
    return t;
}

namespace {
// Twice the area of the triangle p0 p1 p2 (m^2): below this it is a line, not a platform.
double doubled_area(const std::array<Vec3, 3>& p) { return (p[1] - p[0]).cross(p[2] - p[0]).norm(); }
constexpr double min_doubled_area = 1e-8;  // m^2: a triangle of ~0.1 mm sides
}  // namespace

PlatformCheck check_platform(const PlatformDef& def) {
    for (int i = 0; i < 3; ++i) {
        if (!def.a[i].allFinite() || !def.b[i].allFinite())
            return {false, "point A_" + std::to_string(i + 1) + " or B_" + std::to_string(i + 1) + " is not finite"};
        if (!std::isfinite(def.finger_radius[i]) || def.finger_radius[i] <= 0.0)
            return {false, "finger radius R_" + std::to_string(i + 1) + " must be positive (m)"};
    }
    if (!def.rest.allFinite()) return {false, "the rest pose is not finite"};
    if (doubled_area(def.a) < min_doubled_area) return {false, "the static points A_i are collinear"};
    if (doubled_area(def.b) < min_doubled_area) return {false, "the platform points B_i are collinear"};
    const IkResult ik = inverse_kinematics(def, def.rest);
    if (ik.status != IkStatus::ok)
        return {false, std::string("at the rest pose cable ") + std::to_string(ik.cable + 1) + ": " +
                           to_string(ik.status)};
    return {true, {}};
}

}  // namespace contactlab::wearable
