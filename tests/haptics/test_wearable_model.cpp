// test_wearable_model.cpp — seed 003's platform: inverse kinematics (eqs. 1-2) against the
// forward kinematics, the Jacobians (eqs. 3-4) against finite differences, statics (eqs. 5-6)
// against a brute-force equilibrium, the reachable subspace, and degenerate poses and geometries.
#include "haptics/wearable/equilibrium.hpp"
#include "haptics/wearable/finger_stiffness.hpp"
#include "haptics/wearable/kinematics.hpp"
#include "haptics/wearable/plant.hpp"
#include "haptics/wearable/statics.hpp"

#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cmath>
#include <random>

using namespace contactlab::wearable;

namespace {

// Poses in the working range: within +-1 mm laterally, 0..2.5 mm into the pad, +-0.3 rad.
std::vector<Pose> sample_poses(const PlatformDef& def, int n, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> lat(-0.001, 0.001), up(0.0, 0.0025), ang(-0.3, 0.3);
    std::vector<Pose> out;
    while (static_cast<int>(out.size()) < n) {
        Pose xi = def.rest;
        xi(0) += lat(rng);
        xi(1) += lat(rng);
        xi(2) += up(rng);
        xi(3) += ang(rng);
        xi(4) += ang(rng);
        xi(5) += 0.3 * ang(rng);
        // Keep away from eq. 2's singularity q_i -> 2 R_i (dl/dq -> infinity): chords up to 95 %
        // of the finger's diameter, where dl/dq <= 3.2.
        const IkResult ik = inverse_kinematics(def, xi);
        if (ik.status != IkStatus::ok) continue;
        bool inside = true;
        for (int i = 0; i < 3; ++i) inside = inside && ik.q(i) < 0.95 * 2.0 * def.finger_radius[i];
        if (inside) out.push_back(xi);
    }
    return out;
}

// Chords computed here from the definition, sharing nothing with kinematics.cpp but Eigen: the
// platform point rotated by an arbitrary rotation matrix.
Eigen::Vector3d chords(const PlatformDef& def, const Eigen::Vector3d& p, const Eigen::Matrix3d& rot) {
    Eigen::Vector3d q;
    for (int i = 0; i < 3; ++i) q(i) = (p + rot * def.b[i] - def.a[i]).norm();
    return q;
}

}  // namespace

TEST_CASE("wearable IK: eqs. 1-2 at the rest pose by hand, and the assembly check") {
    const PlatformDef def;
    REQUIRE(check_platform(def).ok);
    const IkResult ik = inverse_kinematics(def, def.rest);
    REQUIRE(ik.status == IkStatus::ok);
    // B_1 at Table 2's (-9, -6, -15) mm, A_1 at (-8, -13, 0) mm: d_1 = (-1, 7, -15) mm.
    const double q1 = std::sqrt(1.0 + 49.0 + 225.0) * 1e-3;
    CHECK(ik.q(0) == doctest::Approx(q1).epsilon(1e-12));
    CHECK(ik.l(0) == doctest::Approx(2.0 * 0.010 * std::asin(q1 / 0.020)).epsilon(1e-12));
    CHECK(ik.cables[0].cos_theta == doctest::Approx(15e-3 / q1).epsilon(1e-12));
    // eq. 2's arc is longer than its chord, and shorter than the half circle.
    for (int i = 0; i < 3; ++i) {
        CHECK(ik.l(i) > ik.q(i));
        CHECK(ik.l(i) < M_PI * def.finger_radius[i]);
    }
}

TEST_CASE("wearable IK and FK round trip over the working range") {
    const PlatformDef def;
    int checked = 0;
    for (const Pose& xi : sample_poses(def, 200, 17)) {
        const IkResult ik = inverse_kinematics(def, xi);
        REQUIRE(ik.status == IkStatus::ok);
        Pose guess = def.rest;  // FK holds p_x, p_y, gamma at the guess's values
        guess(0) = xi(0);
        guess(1) = xi(1);
        guess(5) = xi(5);
        const FkResult fk = forward_kinematics(def, ik.l, guess);
        REQUIRE(fk.status == FkStatus::ok);
        // Newton stops at |l(xi) - l| <= 1e-12 m; |dl/dxi|^-1 is below ~100 (m/m, rad/m) here,
        // so the pose is recovered to 1e-10 in m and rad.
        CHECK((fk.xi - xi).cwiseAbs().maxCoeff() < 1e-10);
        ++checked;
    }
    CHECK(checked == 200);
}

TEST_CASE("wearable Jacobians J_p and J_l against central differences") {
    const PlatformDef def;
    const double h = 1e-6;  // m or rad: truncation h^2 |q'''| ~ 1e-12 / (1 cm)^2 ~ 1e-8, rounding eps q / h ~ 1e-11
    for (const Pose& xi : sample_poses(def, 50, 3)) {
        const IkResult ik = inverse_kinematics(def, xi);
        REQUIRE(ik.status == IkStatus::ok);
        const Mat36 jp = jacobian_p(ik), jl = jacobian_l(ik);
        const Eigen::Matrix3d rot = rotation(xi);
        const Eigen::Vector3d p = xi.head<3>();
        for (int a = 0; a < 6; ++a) {
            // A twist along axis a: a translation of p, or a rotation about a fixed S_0 axis
            // (omega), applied as exp(h omega^) R, independent of the Euler angles.
            Eigen::Vector3d qp, qm;
            if (a < 3) {
                const Eigen::Vector3d e = Eigen::Vector3d::Unit(a) * h;
                qp = chords(def, p + e, rot);
                qm = chords(def, p - e, rot);
            } else {
                const Eigen::Vector3d axis = Eigen::Vector3d::Unit(a - 3);
                qp = chords(def, p, Eigen::AngleAxisd(h, axis).toRotationMatrix() * rot);
                qm = chords(def, p, Eigen::AngleAxisd(-h, axis).toRotationMatrix() * rot);
            }
            const Eigen::Vector3d dq = (qp - qm) / (2.0 * h);
            CHECK((jp.col(a) - dq).cwiseAbs().maxCoeff() < 1e-7);
            Eigen::Vector3d dl;
            for (int i = 0; i < 3; ++i) {
                const double r2 = 2.0 * def.finger_radius[i];
                dl(i) = (r2 * std::asin(qp(i) / r2) - r2 * std::asin(qm(i) / r2)) / (2.0 * h);
            }
            CHECK((jl.col(a) - dl).cwiseAbs().maxCoeff() < 1e-7 * 10.0);  // dl/dq <= ~3 here
        }
        // In the seed's coordinates xi: dl/dxi = J_l T(xi).
        const Mat36 jxi = jl * euler_rate_map(xi);
        for (int a = 0; a < 6; ++a) {
            Pose e = Pose::Zero();
            e(a) = h;
            const Eigen::Vector3d dl = (inverse_kinematics(def, xi + e).l - inverse_kinematics(def, xi - e).l) / (2.0 * h);
            CHECK((jxi.col(a) - dl).cwiseAbs().maxCoeff() < 1e-6);
        }
    }
}

TEST_CASE("wearable geometric stiffness: the closed-form sum_i w_i d^2 l_i / dxi^2 against central differences of J_l T") {
    const PlatformDef def;
    // Central differences of dl/dxi = J_l T (checked above against the chords themselves) with
    // step h: truncation h^2 |d^3 (dl/dxi)| ~ 1e-12 x 3 / (1 cm)^3 ~ 3e-6 relative to entries of
    // |d^2 l| ~ 3 / (1 cm) ~ 300 /m, i.e. ~1e-8, and rounding eps |J| / h ~ 1e-10: agreement to
    // 1e-6 of the largest entry is a thousand times what either allows, and a wrong sign, factor
    // or missing term (each at least a few per cent of it over these poses) fails it.
    const double h = 1e-6;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> tension(0.0, 3.0);  // N
    int checked = 0;
    for (const Pose& xi : sample_poses(def, 50, 7)) {
        const IkResult ik = inverse_kinematics(def, xi);
        REQUIRE(ik.status == IkStatus::ok);
        Eigen::Vector3d w(tension(rng), tension(rng), tension(rng));
        if (checked % 5 == 0) w(checked % 3) = 0.0;  // a slack cable
        const Mat6 g = weighted_length_hessian(def, xi, ik, w);
        Mat6 fd;
        for (int a = 0; a < 6; ++a) {
            Pose e = Pose::Zero();
            e(a) = h;
            const IkResult plus = inverse_kinematics(def, xi + e), minus = inverse_kinematics(def, xi - e);
            REQUIRE(plus.status == IkStatus::ok);
            REQUIRE(minus.status == IkStatus::ok);
            fd.col(a) = ((jacobian_l(plus) * euler_rate_map(xi + e)).transpose() * w -
                         (jacobian_l(minus) * euler_rate_map(xi - e)).transpose() * w) / (2.0 * h);
        }
        const double scale = fd.cwiseAbs().maxCoeff();
        REQUIRE(scale > 0.0);
        CHECK((g - fd).cwiseAbs().maxCoeff() <= 1e-6 * scale);
        // Symmetric to rounding (the products D^T D and g g^T round each half on its own).
        CHECK((g - g.transpose()).cwiseAbs().maxCoeff() <= 1e-13 * scale);
        ++checked;
    }
    CHECK(checked == 50);
    // Zero weights, and a pose outside the workspace: zero, never NaN.
    const IkResult rest = inverse_kinematics(def, def.rest);
    CHECK(weighted_length_hessian(def, def.rest, rest, Eigen::Vector3d::Zero()).isZero());
    IkResult bad;
    CHECK(weighted_length_hessian(def, def.rest, bad, Eigen::Vector3d::Ones()).isZero());
}

TEST_CASE("wearable statics: eq. 5 against a brute-force equilibrium of the fingertip spring") {
    // Constant tensions Q do work -Q . l: the platform on the fingertip spring rests at a
    // stationary point of U(xi) = 1/2 (xi - xi_0)^T K (xi - xi_0) + Q . l(xi). Found here by
    // Newton's method on U's finite-difference gradient and Hessian, built from cable lengths
    // alone (no Jacobian, no statics code); at that pose eqs. 5 and 8 must agree.
    const PlatformDef def;
    const Mat6 k = finger_stiffness();
    // Tensions close to balance: the fingertip's rotational stiffness is soft (0.002 N m/rad), so
    // 0.05 N of imbalance on an 8 mm lever already tilts the platform by ~0.2 rad.
    for (const Eigen::Vector3d& q : {Eigen::Vector3d(0.3, 0.3, 0.3), Eigen::Vector3d(0.28, 0.3, 0.25),
                                     Eigen::Vector3d(0.5, 0.45, 0.5)}) {
        auto energy = [&](const Pose& xi) {
            const Pose d = xi - def.rest;
            return 0.5 * d.dot(k * d) + q.dot(inverse_kinematics(def, xi).l);
        };
        Pose xi = def.rest;
        const double h = 1e-5;   // m or rad, for the Hessian (only steers the iteration)
        const double hg = 3e-7;  // m or rad, for the gradient (sets the answer)
        for (int it = 0; it < 60; ++it) {
            Pose g;
            Mat6 hess;
            for (int a = 0; a < 6; ++a) {
                Pose ea = Pose::Zero();
                ea(a) = hg;
                g(a) = (energy(xi + ea) - energy(xi - ea)) / (2.0 * hg);
                ea(a) = h;
                for (int b = 0; b < 6; ++b) {
                    Pose eb = Pose::Zero();
                    eb(b) = h;
                    hess(a, b) = (energy(xi + ea + eb) - energy(xi + ea - eb) - energy(xi - ea + eb) +
                                  energy(xi - ea - eb)) / (4.0 * h * h);
                }
            }
            Pose step = hess.fullPivLu().solve(g);
            const double biggest = step.cwiseAbs().maxCoeff();
            if (biggest > 0.02) step *= 0.02 / biggest;  // at most 0.02 rad (or m) a step
            xi -= step;
        }
        const IkResult ik = inverse_kinematics(def, xi);
        REQUIRE(ik.status == IkStatus::ok);
        const Wrench from_cables = platform_wrench(jacobian_l(ik), q);  // eq. 5
        const Wrench from_finger = finger_wrench(k, def.rest, xi);      // eq. 8
        // The finite-difference gradient is exact to ~hg^2 U''' / 6 ~ 1e-9 N (U''' ~ 1e5 N/m^2 near
        // the wrap limit) and eps U / hg ~ 3e-11 N; on rotations the lever is ~1 cm (1e-11 N m).
        CHECK((from_cables.head<3>() - from_finger.head<3>()).norm() < 1e-8);
        CHECK((from_cables.tail<3>() - from_finger.tail<3>()).norm() < 1e-10);
        CHECK(from_cables(2) < 0.0);  // the fingertip pushes the platform away from the nail
        // Eq. 6 gives the tensions back from that wrench, with no residual.
        const CableForces cf = cable_forces(jacobian_l(ik), from_finger, StaticsDef{1e-8, 1e-10, 1e-9});
        CHECK(cf.status == StaticsStatus::ok);
        CHECK((cf.tension - q).cwiseAbs().maxCoeff() < 1e-7);
    }
}

TEST_CASE("wearable statics: a wrench outside the reachable subspace gets least squares and its residual") {
    const PlatformDef def;
    const IkResult ik = inverse_kinematics(def, def.rest);
    const Mat36 jl = jacobian_l(ik);
    const Eigen::Vector3d q(0.2, 0.3, 0.1);
    const Wrench reachable = platform_wrench(jl, q);
    // A direction orthogonal to the columns of J_l^T: the last left singular vector.
    const Eigen::JacobiSVD<Eigen::Matrix<double, 6, 3>> svd(jl.transpose(), Eigen::ComputeFullU);
    const Wrench orth = svd.matrixU().col(5);
    REQUIRE((jl * orth).norm() < 1e-12);
    const CableForces cf = cable_forces(jl, reachable + 0.05 * orth);
    CHECK(cf.status == StaticsStatus::outside_subspace);
    CHECK(cf.rank == 3);
    CHECK((cf.tension - q).cwiseAbs().maxCoeff() < 1e-12);   // least squares ignores the orthogonal part
    CHECK((cf.residual - 0.05 * orth).norm() < 1e-12);        // ... and reports it
    CHECK(cf.tension.allFinite());
    // A wrench that needs a cable to push.
    const CableForces push = cable_forces(jl, platform_wrench(jl, Eigen::Vector3d(0.2, -0.1, 0.3)));
    CHECK(push.status == StaticsStatus::needs_push);
    CHECK(push.tension(1) == doctest::Approx(-0.1).epsilon(1e-9));
    // NaN in: zeros and a state out.
    Wrench bad = reachable;
    bad(4) = std::nan("");
    const CableForces nan = cable_forces(jl, bad);
    CHECK(nan.status == StaticsStatus::non_finite);
    CHECK(nan.tension.isZero());
    // Two cables made parallel (A_2 = A_1 + (B_2 - B_1) at the rest pose): rank 2.
    PlatformDef par = def;
    par.a[1] = par.a[0] + (par.b[1] - par.b[0]);
    const IkResult pik = inverse_kinematics(par, par.rest);
    REQUIRE(pik.status == IkStatus::ok);
    const CableForces rd = cable_forces(jacobian_l(pik), reachable);
    CHECK(rd.rank <= 3);
    CHECK(rd.tension.allFinite());
    CHECK(rd.residual.allFinite());
}

TEST_CASE("wearable degenerate poses and geometries are states, never NaN") {
    const PlatformDef def;
    // The platform pulled 4 mm further from the nail: chords reach 2 R_i = 20 mm (eq. 2 undefined).
    Pose far = def.rest;
    far(2) -= 0.004;
    const IkResult ik = inverse_kinematics(def, far);
    CHECK(ik.status == IkStatus::cable_cannot_wrap);
    CHECK(ik.cable >= 0);
    CHECK(jacobian_l(ik).isZero());
    Pose nan = def.rest;
    nan(3) = std::nan("");
    CHECK(inverse_kinematics(def, nan).status == IkStatus::non_finite_pose);
    // Forward kinematics asked for lengths no pose has.
    const FkResult fk = forward_kinematics(def, Eigen::Vector3d::Constant(0.05), def.rest);
    CHECK(fk.status != FkStatus::ok);
    CHECK(fk.xi.allFinite());
    // Geometries that cannot be assembled.
    PlatformDef bad = def;
    bad.finger_radius[1] = 0.007;  // 2 R = 14 mm < q = 16.6 mm
    const PlatformCheck c1 = check_platform(bad);
    CHECK_FALSE(c1.ok);
    CHECK(c1.why.find("cable 2") != std::string::npos);
    bad = def;
    bad.b[2] = Vec3{0.0, -0.004, 0.0};  // B_i collinear
    CHECK_FALSE(check_platform(bad).ok);
    bad = def;
    bad.finger_radius[0] = -1.0;
    CHECK_FALSE(check_platform(bad).ok);
    bad = def;
    bad.a[0](0) = std::nan("");
    CHECK_FALSE(check_platform(bad).ok);
    // A stiffness that is not a spring.
    Mat6 k = finger_stiffness();
    CHECK(check_stiffness(k).ok);
    k(3, 3) = -1.0;
    CHECK_FALSE(check_stiffness(k).ok);
}

TEST_CASE("wearable plant equilibrium: taut and slack cables, eqs. 5 and 8 at the answer") {
    const PlatformDef def;
    const Mat6 k = finger_stiffness();
    const Eigen::Vector3d l0 = inverse_kinematics(def, def.rest).l;
    // Cables just reaching their rest lengths: no tension, the platform stays at rest.
    const Equilibrium rest = solve_equilibrium(def, k, l0, def.rest);
    CHECK(rest.status == EquilibriumStatus::ok);
    CHECK((rest.pose - def.rest).norm() < 1e-12);
    CHECK(rest.tension.isZero());
    // Shorten cable 1 by 0.3 mm, leave 2 and 3 longer than they need: 2 and 3 go slack.
    const Eigen::Vector3d lambda = l0 + Eigen::Vector3d(-0.0003, 0.001, 0.001);
    const Equilibrium e = solve_equilibrium(def, k, lambda, def.rest);
    REQUIRE(e.status == EquilibriumStatus::ok);
    CHECK(e.tension(0) > 0.0);
    CHECK(e.slack[1]);
    CHECK(e.slack[2]);
    CHECK(e.tension(1) == 0.0);
    const IkResult ik = inverse_kinematics(def, e.pose);
    const Wrench w5 = platform_wrench(jacobian_l(ik), e.tension), w8 = finger_wrench(k, def.rest, e.pose);
    // Converged to |dU/dxi| <= 1e-10 (N and N m).
    CHECK((w5 - w8).cwiseAbs().maxCoeff() < 1e-9);
    // Taut: all three shortened, the platform rises into the pad.
    const Equilibrium t = solve_equilibrium(def, k, l0 - Eigen::Vector3d::Constant(0.0002), def.rest);
    REQUIRE(t.status == EquilibriumStatus::ok);
    CHECK(t.pose(2) > def.rest(2));
    CHECK(t.tension.minCoeff() > 0.0);
}

TEST_CASE("wearable plant: starting each equilibrium from the last two poses' extrapolation changes nothing but the start") {
    // The plant settles its platform every 0.1 ms, starting Newton from xi_n + (xi_n - xi_n-1)
    // (one iteration instead of two while the motors move). The answer is held to the same
    // gradient tolerance as a solve from the last pose: two poses whose gradients are both within
    // g (1e-10 N, N m per component) differ by at most |H^-1| |dg| <= sqrt(6) 2g / lambda_min(H),
    // and H >= K (the cables add positive semi-definite stiffness; their geometric term is small
    // next to K here): the bound below uses K's smallest eigenvalue, times 10 for that term.
    PlantDef def;
    WearablePlant plant(def);
    const Eigen::SelfAdjointEigenSolver<Mat6> eig(def.stiffness);
    const double lambda_min = eig.eigenvalues().minCoeff();
    REQUIRE(lambda_min > 0.0);
    const double bound = 10.0 * std::sqrt(6.0) * 2.0 * def.equilibrium.gradient_tolerance / lambda_min;
    double worst = 0.0, worst_gradient = 0.0;
    int moved = 0;
    for (int k = 0; k < 3000; ++k) {
        // Torques that reel the cables in and out unequally: the platform presses and tilts.
        const double t = 1e-4 * k;
        // N m at the shafts, within Table 1's stall torque (0.24 mN m).
        const Eigen::Vector3d torque(1e-4 + 1e-4 * std::sin(2 * 3.14159 * 7 * t), 1e-4 + 1e-4 * std::sin(2 * 3.14159 * 11 * t + 1.0),
                                     1.2e-4 + 0.8e-4 * std::cos(2 * 3.14159 * 5 * t));
        const Pose before = plant.pose();
        plant.step(torque, 1e-4);
        const Equilibrium fresh = solve_equilibrium(def.platform, def.stiffness, plant.unstretched_lengths(), before, def.equilibrium);
        REQUIRE(fresh.status == EquilibriumStatus::ok);
        worst = std::max(worst, (plant.pose() - fresh.pose).cwiseAbs().maxCoeff());
        // And the plant's pose is itself an equilibrium to the solver's tolerance: dU/dxi =
        // K (xi - xi_0) + (J_l T)^T k_c max(0, l - lambda), written here from its definition.
        const IkResult ik = inverse_kinematics(def.platform, plant.pose());
        REQUIRE(ik.status == IkStatus::ok);
        const Eigen::Vector3d q = def.equilibrium.cable_stiffness * (ik.l - plant.unstretched_lengths()).cwiseMax(0.0);
        const Pose grad = def.stiffness * (plant.pose() - def.platform.rest) +
                          (jacobian_l(ik) * euler_rate_map(plant.pose())).transpose() * q;
        worst_gradient = std::max(worst_gradient, grad.cwiseAbs().maxCoeff());
        if ((plant.pose() - before).norm() > 1e-7) ++moved;
    }
    MESSAGE("worst difference " << worst << " against a bound of " << bound << "; moved on " << moved
                                << " of 3000 steps; worst gradient " << worst_gradient);
    CHECK(worst_gradient <= def.equilibrium.gradient_tolerance * (1.0 + 1e-9));  // (the solver's own test, up to rounding)
    CHECK(plant.solve_failures() == 0);
    CHECK(moved > 2000);  // the motors moved the platform: the extrapolation was exercised
    CHECK(worst <= bound);
}
