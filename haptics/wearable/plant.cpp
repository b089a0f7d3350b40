// plant.cpp — the simulated wearable platform (see plant.hpp).
#include "haptics/wearable/plant.hpp"

#include <cmath>
#include <stdexcept>

namespace contactlab::wearable {

WearablePlant::WearablePlant(const PlantDef& def) : def_(def), rng_(def.noise_seed) {
    const PlatformCheck pc = check_platform(def.platform);
    if (!pc.ok) throw std::invalid_argument("wearable platform: " + pc.why);
    const StiffnessCheck sc = check_stiffness(def.stiffness);
    if (!sc.ok) throw std::invalid_argument("wearable platform: " + sc.why);
    if (!(def.physics_dt > 0.0)) throw std::invalid_argument("wearable platform: physics_dt must be positive (s)");
    rest_lengths_ = inverse_kinematics(def.platform, def.platform.rest).l;
    eq_.pose = def.platform.rest;
    settle();
}

Eigen::Vector3d WearablePlant::unstretched_lengths() const {
    Eigen::Vector3d lambda;
    for (int i = 0; i < 3; ++i) lambda(i) = rest_lengths_(i) - cable_per_motor_radian(def_.motor) * motors_[i].angle;
    return lambda;
}

void WearablePlant::settle() {
    const Eigen::Vector3d lambda = unstretched_lengths();
    // Newton starts from the last two poses' extrapolation while the cables move (xi_n +
    // (xi_n - xi_n-1): one iteration a solve instead of two, the answer held to the same
    // tolerance), and from the last pose when they stand still (it is the answer: no iteration),
    // when that start fails, or when there is no history.
    Equilibrium next;
    if (previous_valid_ && lambda != settled_lambda_) {
        const Pose guess = 2.0 * eq_.pose - previous_pose_;
        next = solve_equilibrium(def_.platform, def_.stiffness, lambda, guess, def_.equilibrium);
    }
    if (next.status != EquilibriumStatus::ok)
        next = solve_equilibrium(def_.platform, def_.stiffness, lambda, eq_.pose, def_.equilibrium);
    previous_pose_ = eq_.pose;
    previous_valid_ = next.status == EquilibriumStatus::ok;
    if (previous_valid_) settled_lambda_ = lambda;
    // A pose the solver could not reach keeps the last good one (and its tensions): the motors
    // then see the old load for one step rather than a NaN.
    if (next.status == EquilibriumStatus::ok) eq_ = next;
    else ++solve_failures_;
}

void WearablePlant::step(const Eigen::Vector3d& torque, double dt) {
    if (!(dt > 0.0)) return;
    const int n = static_cast<int>(std::ceil(dt / def_.physics_dt - 1e-9));
    const double h = dt / n;
    for (int k = 0; k < n; ++k) {
        for (int i = 0; i < 3; ++i) motors_[i] = motor_step(def_.motor, motors_[i], torque(i), eq_.tension(i), h);
        settle();
        time_ += h;
    }
}

Eigen::Vector3d WearablePlant::read_fsr() {
    const IkResult ik = inverse_kinematics(def_.platform, eq_.pose);
    Eigen::Vector3d f = ik.status == IkStatus::ok ? fsr_model(ik, eq_.tension) : Eigen::Vector3d::Zero();
    if (def_.fsr_noise > 0.0)
        for (int i = 0; i < 3; ++i) f(i) += def_.fsr_noise * noise_(rng_);
    return f;
}

}  // namespace contactlab::wearable
