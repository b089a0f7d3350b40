// test_wearable_control.cpp — seed 003's actuators (Table 1) and its force (Fig. 5) and position
// (Fig. 6) loops, closed around the simulated plant: steady-state errors against the friction
// dead band they follow from, saturation without NaN, and the fault states with zero output.
#include "haptics/wearable/contact_display.hpp"
#include "haptics/wearable/rig.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

using namespace contactlab::wearable;

namespace {
// Friction's dead band on the tension for force control (N): the motor stops once
// |tau_m - Q r / (N eta)| <= tau_f; with the holding feed-forward tau_m - hold = K_p e.
double force_dead_band(const MotorDef& m, const ForceControlDef& f) {
    return m.friction_torque / (f.kp + m.spool_radius / (m.gear_ratio * m.gear_efficiency));
}
bool finite(const WearableRig& rig) {
    return rig.plant().pose().allFinite() && rig.plant().tension().allFinite() && rig.output().torque.allFinite() &&
           rig.estimate().tension.allFinite();
}
}  // namespace

TEST_CASE("wearable motor: Table 1's stall force, no-load speed and friction") {
    const MotorDef m;
    // 0.24 mN m x 16 x 0.8 / 2 mm
    CHECK(stall_cable_force(m) == doctest::Approx(0.24e-3 * 16.0 * 0.8 / 0.002).epsilon(1e-12));
    // Unloaded under a constant torque the shaft settles where the back-EMF takes what friction
    // leaves: omega = (tau - tau_f) omega_0 / tau_stall; J omega_0 / tau_stall = 8.7 ms, so after
    // 0.2 s (23 time constants) it is there to 1e-9.
    MotorState s;
    const double tau = 0.2e-3;
    for (int k = 0; k < 200; ++k) s = motor_step(m, s, tau, 0.0, 1e-3);
    CHECK(s.speed == doctest::Approx((tau - m.friction_torque) * m.no_load_speed / m.stall_torque).epsilon(1e-9));
    // Holding a tension with less than the friction torque to spare: it does not move.
    MotorState held;
    const double q = 0.5;  // N
    for (int k = 0; k < 100; ++k) held = motor_step(m, held, holding_torque(m, q) + 0.5 * m.friction_torque, q, 1e-3);
    CHECK(held.speed == 0.0);
    CHECK(held.angle == 0.0);
    // A command beyond the stall torque is the stall torque; NaN is zero.
    MotorState a, b;
    a = motor_step(m, a, 10.0, 0.0, 1e-3);
    b = motor_step(m, b, m.stall_torque, 0.0, 1e-3);
    CHECK(a.speed == b.speed);
    CHECK(motor_step(m, MotorState{}, std::nan(""), 0.0, 1e-3).speed == 0.0);
}

TEST_CASE("wearable force control: a 0.3 N step settles within friction's dead band (seed: < 2 %)") {
    RigDef def;
    WearableRig rig(def);
    rig.advance(0.05);
    CHECK(rig.plant().tension().isZero());
    rig.command_force(Eigen::Vector3d::Constant(0.3));
    double t90 = -1.0;
    for (int k = 0; k < 400; ++k) {
        rig.advance(1e-3);
        REQUIRE(finite(rig));
        if (t90 < 0.0 && rig.estimate().tension.minCoeff() >= 0.27) t90 = rig.time() - 0.05;
    }
    const double band = force_dead_band(def.plant.motor, def.force);
    MESSAGE("tension " << rig.plant().tension().transpose() << " N, dead band " << band << " N, 90 % after " << t90 << " s");
    for (int i = 0; i < 3; ++i) {
        CHECK(std::abs(rig.plant().tension()(i) - 0.3) <= band * 1.01);
        CHECK(std::abs(rig.plant().tension()(i) - 0.3) < 0.02 * 0.3);
        // Noise-free readings: the estimate is the plant's tension (Newton to 1e-12).
        CHECK(std::abs(rig.estimate().tension(i) - rig.plant().tension()(i)) < 1e-9);
    }
    CHECK(t90 > 0.0);
    CHECK(t90 < 0.1);  // the seed's rise is about 0.1 s
    CHECK(rig.output().status == ControlStatus::ok);
    CHECK(rig.plant().solve_failures() == 0);
}

TEST_CASE("wearable force control: a reference the motors cannot quite hold saturates without NaN") {
    RigDef def;
    WearableRig rig(def);
    const MotorDef& m = def.plant.motor;
    // 1.5 N is below the stall force (1.536 N) but holding it takes more than stall less friction:
    // the spool stops where Q r / (N eta) = tau_stall - tau_f.
    rig.command_force(Eigen::Vector3d::Constant(1.5));
    bool saw_saturation = false;
    for (int k = 0; k < 500; ++k) {
        rig.advance(1e-3);
        REQUIRE(finite(rig));
        saw_saturation = saw_saturation || rig.output().status == ControlStatus::saturated;
    }
    CHECK(saw_saturation);
    // At the stall torque the spool sticks anywhere its friction holds: from (tau_stall - tau_f) /
    // (r / N eta) = 1.408 N up; the PD's pull ends at the reference plus force control's dead band.
    const double reachable = (m.stall_torque - m.friction_torque) / holding_torque(m, 1.0);
    const double band = force_dead_band(m, def.force);
    for (int i = 0; i < 3; ++i) {
        CHECK(rig.plant().tension()(i) >= 0.999 * reachable);
        CHECK(rig.plant().tension()(i) <= 1.5 + band);
    }
    CHECK(rig.output().torque.cwiseAbs().maxCoeff() <= m.stall_torque);
}

TEST_CASE("wearable force control faults: above stall, non-finite, negative, a faulted estimate") {
    RigDef def;
    WearableRig rig(def);
    rig.command_force(Eigen::Vector3d(0.2, 2.0, 0.2));  // 2 N > 1.536 N on cable 2
    rig.advance(0.1);
    CHECK(rig.output().status == ControlStatus::fault_above_stall);
    CHECK(rig.output().cable == 1);
    CHECK(rig.output().torque.isZero());
    CHECK(rig.plant().tension().isZero());
    // A valid reference again: the loop resumes.
    rig.command_force(Eigen::Vector3d::Constant(0.2));
    rig.advance(0.2);
    CHECK(rig.output().status == ControlStatus::ok);
    CHECK(std::abs(rig.plant().tension()(1) - 0.2) <= force_dead_band(def.plant.motor, def.force) * 1.01);
    rig.command_force(Eigen::Vector3d(0.2, std::nan(""), 0.2));
    rig.advance(0.02);
    CHECK(rig.output().status == ControlStatus::fault_non_finite);
    CHECK(rig.output().torque.isZero());
    CHECK(finite(rig));
    // Negative: raised to zero, reported, the cable goes slack.
    ForceController fc(def.force, def.plant.motor);
    Estimate e;
    e.pose = def.plant.platform.rest;
    const ControlOutput neg = fc.step(Eigen::Vector3d(-0.1, 0.0, 0.0), e, 1e-3);
    CHECK(neg.status == ControlStatus::reference_clamped);
    CHECK(neg.torque.isZero());
    e.status = EstimateStatus::reading_out_of_range;
    e.cable = 2;
    const ControlOutput bad = fc.step(Eigen::Vector3d::Constant(0.3), e, 1e-3);
    CHECK(bad.status == ControlStatus::fault_estimate);
    CHECK(bad.cable == 2);
    CHECK(bad.torque.isZero());
}

TEST_CASE("wearable position control: the cables settle on IK's lengths within friction's dead band") {
    RigDef def;
    WearableRig rig(def);
    const PlatformDef& p = def.plant.platform;
    Pose target = p.rest;
    target(2) += 0.0006;  // 0.6 mm into the pad
    target(3) += 0.03;    // roll (rad)
    target(4) -= 0.02;    // pitch (rad)
    rig.command_pose(target);
    for (int k = 0; k < 600; ++k) {
        rig.advance(1e-3);
        REQUIRE(finite(rig));
    }
    CHECK(rig.mode() == RigMode::position);
    // The controller's IK target: xi_r on the actuated freedoms (p_z, roll, pitch), the estimate
    // (here exact: noise-free readings) on the fingertip's own (p_x, p_y, gamma).
    const Pose& actual = rig.plant().pose();
    Pose ik_target = target;
    ik_target(0) = actual(0);
    ik_target(1) = actual(1);
    ik_target(5) = actual(5);
    const Eigen::Vector3d lr = inverse_kinematics(p, ik_target).l;
    const Eigen::Vector3d l = inverse_kinematics(p, actual).l;
    // With the holding torque the PD carries only friction: |l - l_r| <= tau_f / K_p (17 um).
    const double band = def.plant.motor.friction_torque / def.position.kp;
    MESSAGE("cable length errors " << (l - lr).transpose() << " m, band " << band << " m; pose "
                                   << actual.transpose() << " for " << target.transpose());
    CHECK((l - lr).cwiseAbs().maxCoeff() <= 1.05 * band);
    // So the actuated freedoms sit where xi_r asks, to |J_act^-1| times the length band.
    const Mat36 jxi = jacobian_l(inverse_kinematics(p, actual)) * euler_rate_map(actual);
    Eigen::Matrix3d jact;
    for (int k = 0; k < 3; ++k) jact.col(k) = jxi.col(2 + k);
    const Eigen::Matrix3d inv = jact.inverse();
    for (int k = 0; k < 3; ++k)
        CHECK(std::abs(actual(2 + k) - target(2 + k)) <= 1.05 * band * inv.row(k).cwiseAbs().sum());
    // Forward kinematics of l_r with the fingertip's freedoms held gives that pose back.
    const FkResult fk = forward_kinematics(p, lr, actual);
    REQUIRE(fk.status == FkStatus::ok);
    CHECK((fk.xi.segment<3>(2) - target.segment<3>(2)).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("wearable position control: a pose off the pad leaves the cables slack, an unreachable one faults") {
    RigDef def;
    WearableRig rig(def);
    Pose off = def.plant.platform.rest;
    off(2) -= 0.001;  // 1 mm below the pad: the fingertip does not resist, nothing to hold
    rig.command_pose(off);
    rig.advance(0.5);
    CHECK(finite(rig));
    CHECK(rig.plant().tension().isZero());
    CHECK(rig.output().torque.isZero());
    for (const MotorState& m : rig.plant().motors()) CHECK(std::abs(m.angle) < 1e-9);  // no runaway
    Pose far = def.plant.platform.rest;
    far(2) -= 0.01;  // chords beyond 2 R_i
    rig.command_pose(far);
    rig.advance(0.05);
    CHECK(rig.output().status == ControlStatus::fault_unreachable_pose);
    CHECK(rig.output().torque.isZero());
    CHECK(finite(rig));
}

TEST_CASE("wearable rig: references take effect at the 100 Hz link's ticks") {
    RigDef def;
    WearableRig rig(def);
    rig.advance(0.011);   // PD ticks at 0..10 ms, link ticks at 0 and 10 ms
    rig.command_force(Eigen::Vector3d::Constant(0.3));
    rig.advance(0.008);   // PD ticks at 11..18 ms: not yet
    CHECK(rig.force_reference().isZero());
    CHECK(rig.plant().tension().isZero());
    rig.advance(0.002);   // 19 and 20 ms: the link tick at 20 ms delivers it
    CHECK(rig.force_reference() == Eigen::Vector3d::Constant(0.3));
}

TEST_CASE("wearable contact display: the surface's slope seen from the pad, the press from the force") {
    // A floor (force straight up) under a level finger: no tilt; 1 N presses 0.5 mm at 2 N/mm.
    PlatformPoseCommand p = contact_to_platform(0.0, 1.0, 0.0);
    CHECK(p.contact);
    CHECK(std::abs(p.roll) < 1e-15);
    CHECK(p.press == doctest::Approx(0.0005).epsilon(1e-12));
    // A surface rising toward the fingertip by 0.3 rad: normal (-sin, cos), roll +0.3.
    p = contact_to_platform(-std::sin(0.3), std::cos(0.3), 0.0);
    CHECK(p.roll == doctest::Approx(0.3).epsilon(1e-12));
    // The finger tilted by phi over a floor: the floor slopes away from the fingertip, roll -phi.
    p = contact_to_platform(0.0, 1.0, 0.2);
    CHECK(p.roll == doctest::Approx(-0.2).epsilon(1e-12));
    // What the platform cannot show is clamped; no force, or NaN, is no contact (rest).
    const ContactDisplayDef def;
    p = contact_to_platform(-1.0, 0.1, 0.0);
    CHECK(p.roll == doctest::Approx(def.max_tilt));
    CHECK(contact_to_platform(0.0, 100.0, 0.0).press == def.max_press);
    CHECK_FALSE(contact_to_platform(0.0, 0.0, 0.0).contact);
    const PlatformPoseCommand nan = contact_to_platform(std::nan(""), 1.0, 0.0);
    CHECK_FALSE(nan.contact);
    CHECK(nan.press == 0.0);
    CHECK(nan.roll == 0.0);
}

TEST_CASE("wearable contact display state: the tensions that hold the commanded pose balance the fingertip") {
    const PlatformDef p;
    const Mat6 k = finger_stiffness();
    const PlatformDisplayState st = platform_display_state(-std::sin(0.1), std::cos(0.1), 0.0, p, k);
    REQUIRE(st.reachable);
    CHECK(st.command.roll == doctest::Approx(0.1).epsilon(1e-12));
    // Eq. 5 with these tensions reproduces the fingertip's wrench (eq. 8) up to the part outside
    // the cables' reach, which the statics reports.
    const IkResult ik = inverse_kinematics(p, st.pose);
    const CableForces cf = cable_forces(jacobian_l(ik), finger_wrench(k, p.rest, st.pose));
    CHECK((cf.tension.cwiseMax(0.0) - st.tension).norm() < 1e-15);
    CHECK(st.tension.minCoeff() >= 0.0);
    CHECK(st.tension.sum() > 0.0);  // pressed: the cables pull
    // Free space: rest, nothing pulls.
    const PlatformDisplayState free = platform_display_state(0.0, 0.0, 0.0, p, k);
    CHECK_FALSE(free.command.contact);
    CHECK(free.tension.isZero());
    CHECK(free.pose == p.rest);
}

TEST_CASE("contact display: every commanded pose is one the platform can take, light or heavy, on any slope") {
    // The seed's platform reaches -0.44..+0.88 rad of roll at rest (pressed further, more): a
    // light touch on a surface sloping down toward the fingertip by more than 25 degrees used to
    // ask for -0.5 rad, which the cables cannot wrap, and the device faulted.
    const ContactDisplayDef def;
    int clamped_by_reach = 0;
    for (int deg = 0; deg < 360; ++deg) {
        for (double f : {2e-4, 1e-2, 0.3, 1.5, 5.0}) {  // N (min_force is 1e-4)
            for (double phi : {-0.6, 0.0, 0.6}) {       // rad
                const double a = deg * 3.141592653589793 / 180.0;
                const double fx = f * std::cos(a), fy = f * std::sin(a);
                const PlatformPoseCommand c = contact_to_platform(fx, fy, phi);
                REQUIRE(c.contact);
                Pose xi = def.platform.rest;
                xi(2) += c.press;
                xi(3) += c.roll;
                INFO("force angle " << deg << " deg, " << f << " N, phi " << phi << ": roll " << c.roll);
                CHECK(inverse_kinematics(def.platform, xi).status == IkStatus::ok);
                CHECK(std::abs(c.roll) <= def.max_tilt);
                // The roll asked for before the reach (straight down, angle(F) - pi/2 wraps to -pi).
                const double asked = std::clamp(
                    std::remainder(std::atan2(fy, fx) - (phi + 0.5 * 3.141592653589793), 2 * 3.141592653589793),
                    -def.max_tilt, def.max_tilt);
                if (std::abs(c.roll - asked) > 1e-12) {
                    ++clamped_by_reach;
                    // Only ever toward zero, keeping the slope's sign, and to the reach's edge:
                    // 1e-3 rad further is out of reach.
                    CHECK(c.roll * asked >= 0.0);
                    CHECK(std::abs(c.roll) < std::abs(asked));
                    Pose beyond = xi;
                    beyond(3) += asked > 0 ? 1e-3 : -1e-3;
                    CHECK(inverse_kinematics(def.platform, beyond).status != IkStatus::ok);
                }
            }
        }
    }
    CHECK(clamped_by_reach > 0);  // the light touches on steep down-slopes
    // A 0.4636 rad (26.6 degree) down-slope touched lightly: the reach at rest, -0.442 rad.
    const PlatformPoseCommand light = contact_to_platform(0.01 * std::sin(0.4636), 0.01 * std::cos(0.4636), 0.0);
    CHECK(light.roll == doctest::Approx(-0.442).epsilon(0.005));
}
