// test_wearable_estimation.cpp — seed 003 Fig. 4: Q-hat and xi-hat from three FSR readings
// (eq. 7 inverted, eq. 5, eq. 8), against a known pose and tensions, with seeded sensor noise, and
// its fault states.
#include "haptics/wearable/equilibrium.hpp"
#include "haptics/wearable/estimation.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace contactlab::wearable;

namespace {
// A known truth: the plant's equilibrium with the cables shortened by `pull` (m) from rest. At it
// eqs. 5 and 8 hold (test_wearable_model.cpp), so it is a pose the estimator's model admits.
Equilibrium truth(const PlatformDef& def, const Mat6& k, const Eigen::Vector3d& pull) {
    const Eigen::Vector3d l0 = inverse_kinematics(def, def.rest).l;
    return solve_equilibrium(def, k, l0 - pull, def.rest);
}
}  // namespace

TEST_CASE("wearable estimation: the Newton residual's closed-form Jacobian against central differences") {
    const PlatformDef def;
    const Mat6 k = finger_stiffness();
    const EstimatorDef est;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> lat(-0.001, 0.001), up(0.0, 0.0025), ang(-0.3, 0.3), reading(0.0, 3.0);
    const double h = 3e-7;  // m or rad
    int checked = 0;
    double worst = 0.0;
    while (checked < 40) {
        Pose xi = def.rest;
        xi(0) += lat(rng), xi(1) += lat(rng), xi(2) += up(rng), xi(3) += ang(rng), xi(4) += ang(rng), xi(5) += 0.3 * ang(rng);
        const Eigen::Vector3d f(reading(rng), reading(rng), checked % 4 == 0 ? 0.0 : reading(rng));
        const Eq8Residual at = eq8_residual(est, def, k, f, xi);
        if (!at.ok) continue;
        Mat6 fd;
        bool inside = true;
        for (int a = 0; a < 6 && inside; ++a) {
            Pose e = Pose::Zero();
            e(a) = h;
            const Eq8Residual plus = eq8_residual(est, def, k, f, xi + e), minus = eq8_residual(est, def, k, f, xi - e);
            inside = plus.ok && minus.ok;
            // The readings' part only (K (xi - xi_0) is linear, its derivative K exactly): left
            // in, its rounding would swamp the rest.
            if (inside)
                fd.col(a) = ((plus.value - k * (xi + e - def.rest)) - (minus.value - k * (xi - e - def.rest))) / (2.0 * h);
        }
        if (!inside) continue;
        // The tensions' geometric stiffness and their change with cos(theta_i). Central
        // differences carry truncation ~h^2 |third derivative| and rounding ~eps |T^T J_l^T Q| / h
        // (~1e-16 x 1 N / 3e-7 ~ 3e-10 N per m or rad). Measured over these poses, the largest
        // difference scales as h^2 (2e-5, 2e-7, 2e-9 of the largest entry at h = 1e-5, 1e-6,
        // 1e-7): truncation, about 2e-8 at this h. 1e-6 is fifty times that, and a dropped term or
        // a wrong sign (each at least a few per cent of it over these poses) fails.
        const Mat6 analytic = at.jacobian - k, numeric = fd;
        const double scale = numeric.cwiseAbs().maxCoeff();
        REQUIRE(scale > 0.0);
        const double err = (analytic - numeric).cwiseAbs().maxCoeff() / scale;
        worst = std::max(worst, err);
        CHECK(err <= 1e-6);
        ++checked;
    }
    MESSAGE("worst relative difference " << worst);
    // Outside the workspace: not ok, zeros, never NaN.
    Pose far = def.rest;
    far(2) = -0.5;
    const Eq8Residual out = eq8_residual(est, def, k, Eigen::Vector3d::Ones(), far);
    CHECK_FALSE(out.ok);
    CHECK(out.jacobian.isZero());
}

TEST_CASE("wearable estimation recovers a known pose and cable tensions from exact FSR readings") {
    const PlatformDef def;
    const Mat6 k = finger_stiffness();
    for (const Eigen::Vector3d& pull : {Eigen::Vector3d(0.0006, 0.0006, 0.0006), Eigen::Vector3d(0.0008, 0.0005, 0.0007),
                                        Eigen::Vector3d(0.0003, 0.0009, 0.0004)}) {
        const Equilibrium t = truth(def, k, pull);
        REQUIRE(t.status == EquilibriumStatus::ok);
        REQUIRE(t.tension.minCoeff() > 0.05);
        const Eigen::Vector3d fsr = fsr_model(inverse_kinematics(def, t.pose), t.tension);  // eq. 7
        const Estimate e = estimate(EstimatorDef{}, def, k, fsr, def.rest);
        REQUIRE(e.status == EstimateStatus::ok);
        // Newton stops at a residual of 1e-12 (N, N m); the softest direction (0.002 N m/rad, stiffened
        // by the cables) turns that into < 1e-9 rad.
        CHECK((e.pose - t.pose).cwiseAbs().maxCoeff() < 1e-8);
        CHECK((e.tension - t.tension).cwiseAbs().maxCoeff() < 1e-9);
        CHECK((e.length - inverse_kinematics(def, t.pose).l).cwiseAbs().maxCoeff() < 1e-9);
        CHECK_FALSE(e.slack[0]);
    }
}

TEST_CASE("wearable estimation with seeded FSR noise stays within the noise's linear bound") {
    const PlatformDef def;
    const Mat6 k = finger_stiffness();
    const Equilibrium t = truth(def, k, Eigen::Vector3d(0.0007, 0.0006, 0.0007));
    REQUIRE(t.status == EquilibriumStatus::ok);
    const IkResult ik = inverse_kinematics(def, t.pose);
    const Eigen::Vector3d exact = fsr_model(ik, t.tension);
    const double sigma = 0.003;  // N: ~0.3 % of the FSR 400's 10 N span
    // Bounds, from eq. 7 and eq. 8 linearised: |dQ_i| <= |dF_i| / cos(theta_i); the pose moves by
    // K^-1 J_l^T dQ at most (the cables' geometric stiffness only stiffens this platform, see the
    // equilibrium's Hessian), with |dF_i| <= 4 sigma (6e-5 two-sided per draw).
    const Mat36 jl = jacobian_l(ik);
    Eigen::Vector3d dq_max;
    for (int i = 0; i < 3; ++i) dq_max(i) = 4.0 * sigma / ik.cables[i].cos_theta;
    const double slack_margin = 1.2;  // the non-linear terms over the +-4 sigma range (<20 %)
    Pose pose_max;
    for (int a = 0; a < 6; ++a) pose_max(a) = slack_margin * jl.col(a).cwiseAbs().dot(dq_max) / k(a, a);
    std::mt19937_64 rng(2012);
    std::normal_distribution<double> noise(0.0, sigma);
    Pose previous = def.rest;
    double worst_q = 0.0, worst_tilt = 0.0;
    for (int draw = 0; draw < 200; ++draw) {
        Eigen::Vector3d fsr = exact;
        for (int i = 0; i < 3; ++i) fsr(i) += std::clamp(noise(rng), -4.0 * sigma, 4.0 * sigma);
        const Estimate e = estimate(EstimatorDef{}, def, k, fsr, previous);
        REQUIRE(e.status == EstimateStatus::ok);
        previous = e.pose;  // as on line: each sample starts from the last estimate
        for (int i = 0; i < 3; ++i) CHECK(std::abs(e.tension(i) - t.tension(i)) <= slack_margin * dq_max(i));
        for (int a = 0; a < 6; ++a) CHECK(std::abs(e.pose(a) - t.pose(a)) <= pose_max(a));
        worst_q = std::max(worst_q, (e.tension - t.tension).cwiseAbs().maxCoeff());
        worst_tilt = std::max(worst_tilt, std::abs(e.pose(3) - t.pose(3)));
    }
    MESSAGE("worst |dQ| " << worst_q << " N, worst roll error " << worst_tilt << " rad at sigma " << sigma << " N");
    CHECK(worst_q > 0.0);  // the noise reached the estimate
}

TEST_CASE("wearable estimation: the seed's one pass per sample oscillates on the soft fingertip, Newton does not") {
    const PlatformDef def;
    const Equilibrium t = truth(def, finger_stiffness(), Eigen::Vector3d(0.0006, 0.0006, 0.0006));
    REQUIRE(t.status == EquilibriumStatus::ok);
    const Eigen::Vector3d fsr = fsr_model(inverse_kinematics(def, t.pose), t.tension);
    EstimatorDef seed;
    seed.method = EstimatorMethod::seed_one_pass;
    // With the seed's k I read in mm (0.002 N m/rad) the held reading never settles ...
    Pose xi = def.rest;
    double last_jump = 0.0;
    bool faulted = false;
    for (int j = 0; j < 40; ++j) {
        const Estimate e = estimate(seed, def, finger_stiffness(), fsr, xi);
        faulted = faulted || e.status != EstimateStatus::ok;
        CHECK(e.pose.allFinite());
        last_jump = (e.pose - xi).cwiseAbs().maxCoeff();
        xi = e.pose;
    }
    CHECK((faulted || last_jump > 0.1));
    // ... while on a fingertip 25x stiffer in rotation the same passes converge on Newton's answer.
    FingerStiffnessDef stiff;
    stiff.k_rotation = 0.05;  // N m/rad
    const Mat6 ks = finger_stiffness(stiff);
    const Equilibrium ts = truth(def, ks, Eigen::Vector3d(0.0006, 0.0006, 0.0006));
    const Eigen::Vector3d fs = fsr_model(inverse_kinematics(def, ts.pose), ts.tension);
    xi = def.rest;
    for (int j = 0; j < 200; ++j) xi = estimate(seed, def, ks, fs, xi).pose;
    CHECK((xi - ts.pose).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((estimate(EstimatorDef{}, def, ks, fs, def.rest).pose - ts.pose).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("wearable estimation faults: out of range, non-finite, a cable in the platform's plane, slack") {
    const PlatformDef def;
    const Mat6 k = finger_stiffness();
    Pose previous = def.rest;
    previous(2) += 0.0005;
    const EstimatorDef ed;
    for (const Eigen::Vector3d& bad : {Eigen::Vector3d(0.2, 12.0, 0.2), Eigen::Vector3d(0.2, 0.2, -0.5)}) {
        const Estimate e = estimate(ed, def, k, bad, previous);
        CHECK(e.status == EstimateStatus::reading_out_of_range);
        CHECK(e.tension.isZero());
        CHECK(e.pose == previous);
    }
    const Estimate n = estimate(ed, def, k, Eigen::Vector3d(0.2, std::nan(""), 0.2), previous);
    CHECK(n.status == EstimateStatus::non_finite_reading);
    CHECK(n.cable == 1);
    CHECK(n.tension.isZero());
    // Nothing pressed (and noise just below zero): zero tensions, the rest pose, all slack.
    const Estimate z = estimate(ed, def, k, Eigen::Vector3d(0.0, -0.01, 0.0), def.rest);
    CHECK(z.status == EstimateStatus::ok);
    CHECK(z.tension.isZero());
    CHECK((z.pose - def.rest).norm() < 1e-15);
    CHECK((z.slack[0] && z.slack[1] && z.slack[2]));
    // A_1 moved into the platform's plane: cable 1 runs parallel to the platform, cos(theta_1) = 0.
    PlatformDef flat = def;
    flat.a[0] = Vec3{-0.030, -0.006, -0.015};
    flat.finger_radius[0] = 0.02;
    REQUIRE(check_platform(flat).ok);
    const Estimate p = estimate(ed, flat, k, Eigen::Vector3d(0.1, 0.1, 0.1), flat.rest);
    CHECK(p.status == EstimateStatus::cable_parallel_to_platform);
    CHECK(p.cable == 0);
    CHECK(p.tension.isZero());
    CHECK(p.pose.allFinite());
}
