// plant.hpp — the simulated wearable platform of seed 003: three motors (motor.hpp) winding
// elastic cables that hold the massless platform against the fingertip spring
// (equilibrium.hpp), and three FSRs reading eq. 7 with seeded Gaussian noise. Pure physics, for
// the control tests and the simulated device (drivers/sim).
//
// Each cable's unstretched length is lambda_i = l_i(xi_0) - (r / N) theta_i: at motor angle 0 the
// cables are just taut at the rest pose, reeling in (theta > 0) shortens them.
#pragma once

#include "haptics/wearable/equilibrium.hpp"
#include "haptics/wearable/estimation.hpp"
#include "haptics/wearable/motor.hpp"

#include <cstdint>
#include <random>

namespace contactlab::wearable {

struct PlantDef {
    PlatformDef platform;
    Mat6 stiffness = finger_stiffness();
    MotorDef motor;
    EquilibriumDef equilibrium;
    double fsr_noise = 0.0;       // N, standard deviation of each reading's Gaussian noise
    std::uint64_t noise_seed = 1; // the noise's generator seed (same seed, same readings)
    double physics_dt = 1e-4;     // s: step() subdivides longer steps into ones no longer than this
};

class WearablePlant {
public:
    // Throws std::invalid_argument (with check_platform's or check_stiffness's reason) when the
    // platform cannot be assembled or K is not a spring.
    explicit WearablePlant(const PlantDef& def);

    // Advances dt (s) with the motor torques tau_m (N m at the shafts) held.
    void step(const Eigen::Vector3d& torque, double dt);

    // The three FSR readings now (N): eq. 7 at the platform's pose, plus noise.
    Eigen::Vector3d read_fsr();

    const PlantDef& def() const noexcept { return def_; }
    void set_fsr_noise(double n) noexcept { def_.fsr_noise = n; }  // N, from the next reading
    const Pose& pose() const noexcept { return eq_.pose; }
    const Eigen::Vector3d& tension() const noexcept { return eq_.tension; }
    const Equilibrium& equilibrium() const noexcept { return eq_; }
    const std::array<MotorState, 3>& motors() const noexcept { return motors_; }
    Eigen::Vector3d unstretched_lengths() const;  // lambda (m)
    double time() const noexcept { return time_; }
    // Steps whose equilibrium did not converge (the last good pose was kept).
    int solve_failures() const noexcept { return solve_failures_; }

private:
    void settle();
    PlantDef def_;
    Eigen::Vector3d rest_lengths_;
    std::array<MotorState, 3> motors_{};
    Equilibrium eq_;
    Pose previous_pose_ = Pose::Zero();  // the pose before the last settle (Newton's start: settle())
    bool previous_valid_ = false;
    Eigen::Vector3d settled_lambda_ = Eigen::Vector3d::Zero();  // m, the unstretched lengths eq_ is for
    std::mt19937_64 rng_;
    std::normal_distribution<double> noise_{0.0, 1.0};
    double time_ = 0.0;
    int solve_failures_ = 0;
};

}  // namespace contactlab::wearable
