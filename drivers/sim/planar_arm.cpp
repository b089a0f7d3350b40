// planar_arm.cpp — 2-link arm dynamics (see planar_arm.hpp).
#include "drivers/sim/planar_arm.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace contactlab::drivers::sim {

namespace {
// The encoders' quantised angles (k counts, k step rad) repeat from trial to trial, and their sines
// were a twentieth of a simulated trial's arm (two sincos a tick: the counts change nearly every
// tick). One turn's are made once a process, at the rig's 65,536 counts a turn (1 MB), with the
// same expressions as a direct call: the same bits. Count 0 is left to the direct call (its angle
// may be -0).
constexpr int kTableCounts = 65536;
const double* turn_table() {
    static const std::vector<double> table = [] {
        std::vector<double> t(2 * static_cast<std::size_t>(kTableCounts));
        const double step = kTwoPi / kTableCounts;  // rad, as quantise's
        for (int k = 1; k < kTableCounts; ++k) {
            const double q = static_cast<double>(k) * step;
            t[2 * static_cast<std::size_t>(k)] = std::sin(q);
            t[2 * static_cast<std::size_t>(k) + 1] = std::cos(q);
        }
        return t;
    }();
    return table.data();
}
}  // namespace

PlanarArm::PlanarArm(const PlanarArmParams& p) : p_(p) {
    update_trig();
    // Made here, off the servo thread: a tick reads it, never builds it.
    if (p_.encoder_counts == kTableCounts) turn_table_ = turn_table();
}

void PlanarArm::update_trig() {
    s1_ = std::sin(q1_), c1_ = std::cos(q1_);
    s12_ = std::sin(q1_ + q2_), c12_ = std::cos(q1_ + q2_);
    turns_since_refresh_ = 0;
}

namespace {
// A substep turns a joint by |w| h: at most a few rad/s over 0.1 ms, ~1e-4 rad. Below kSmallTurn
// (rad) sin and cos of the turn come from their series, whose first omitted terms (d^7 / 5040,
// d^8 / 40320) are below 2e-18 there: the rotation is exact to rounding, about an ulp a substep.
constexpr double kSmallTurn = 1e-2;
// Every this many turns the sines are taken from the library again, so the rounding of the
// rotations (an ulp or two each) never accumulates past this many ulps.
constexpr int kTrigRefresh = 16;

// (s, c) turned by d (rad), |d| < kSmallTurn. The series in Horner form with the coefficients as
// constants: divisions (a tenth of a substep's time when written d2 / 6 ...) are not needed.
// T is a double, or a pair of them (Pair) turned at once, each lane rounding as a double would.
template <class T>
inline void rotate(T& s, T& c, T d) {
    constexpr double s3 = -1.0 / 6.0, s5 = 1.0 / 120.0;
    constexpr double c2 = -1.0 / 2.0, c4 = 1.0 / 24.0, c6 = -1.0 / 720.0;
    const T d2 = d * d;
    const T sd = d + d * d2 * (s3 + d2 * s5);
    const T cd = 1.0 + d2 * (c2 + d2 * (c4 + d2 * c6));
    const T s0 = s;
    s = s0 * cd + c * sd;
    c = c * cd - s0 * sd;
}

// Two doubles in one register (GCC's and Clang's vector extension): the shoulder's and the
// forearm's turns are the same series on independent numbers, so one pass of two-lane operations
// does both (the same bits: each lane's operations are the scalar ones, in the same order; the
// two scalar passes were a quarter of a substep).
using Pair = double __attribute__((vector_size(16)));

}  // namespace

void PlanarArm::turn_trig(double d1, double d12) {
    if (++turns_since_refresh_ >= kTrigRefresh || !(std::abs(d1) < kSmallTurn) || !(std::abs(d12) < kSmallTurn)) {
        update_trig();
        return;
    }
    Pair s{s1_, s12_}, c{c1_, c12_};
    rotate(s, c, Pair{d1, d12});
    s1_ = s[0], s12_ = s[1];
    c1_ = c[0], c12_ = c[1];
}

Vec2 PlanarArm::endpoint_of(double q1, double q2) const {
    return endpoint_from(std::sin(q1), std::cos(q1), std::sin(q1 + q2), std::cos(q1 + q2));
}

bool PlanarArm::place_at(Vec2 x) {
    const Vec2 d = x - p_.base;
    const double r2 = glm::dot(d, d);
    const double c2 = (r2 - p_.l1 * p_.l1 - p_.l2 * p_.l2) / (2.0 * p_.l1 * p_.l2);
    if (!(std::abs(c2) < 1.0)) return false;
    // Elbow bent to the left (q2 > 0): the shoulder sits below and the elbow away from the scene.
    const double q2 = std::acos(c2);
    const double q1 = std::atan2(d.y, d.x) - std::atan2(p_.l2 * std::sin(q2), p_.l1 + p_.l2 * std::cos(q2));
    q1_ = q1;
    q2_ = q2;
    update_trig();
    w1_ = w2_ = 0.0;
    return true;
}

void PlanarArm::count_trig(double k, double q, double& s, double& c) const {
    const double step = kTwoPi / p_.encoder_counts;
    if (turn_table_ != nullptr && k >= 1.0 && k < kTableCounts && k * step == q) {
        const double* e = turn_table_ + 2 * static_cast<std::size_t>(k);
        s = e[0], c = e[1];
        return;
    }
    s = std::sin(q), c = std::cos(q);
}

const PlanarArm::MeasuredTrig& PlanarArm::measured_trig() const {
    const double step = kTwoPi / p_.encoder_counts;
    const double k1 = std::floor(q1_ / step), k2 = std::floor(q2_ / step);  // counts
    const double q1 = k1 * step, q2 = k2 * step;  // rad, quantised
    if (!(measured_.valid && measured_.q1 == q1 && measured_.q2 == q2)) {
        measured_.q1 = q1, measured_.q2 = q2, measured_.valid = true;
        count_trig(k1, q1, measured_.s1, measured_.c1);
        // q1 + q2 is k1 + k2 counts, and mostly the same double as (k1 + k2) step: then the table's.
        count_trig(k1 + k2, q1 + q2, measured_.s12, measured_.c12);
    }
    return measured_;
}

Vec2 PlanarArm::measured_endpoint() const {
    // endpoint_of at the quantised angles, from their kept sines.
    const MeasuredTrig& m = measured_trig();
    return endpoint_from(m.s1, m.c1, m.s12, m.c12);
}

void PlanarArm::command_force(Vec2 f) {
    // The controller only knows the measured angles, so J is taken there.
    const MeasuredTrig& m = measured_trig();
    double J[2][2];
    jacobian_from(m.s1, m.c1, m.s12, m.c12, J);
    const double t1 = J[0][0] * f.x + J[1][0] * f.y;
    const double t2 = J[0][1] * f.x + J[1][1] * f.y;
    tau1_ = std::clamp(t1, -p_.max_torque, p_.max_torque);
    tau2_ = std::clamp(t2, -p_.max_torque, p_.max_torque);
}

Vec2 PlanarArm::applied_force() const {
    // F = J^-T tau at the true configuration.
    double J[2][2];
    jacobian_now(J);
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    if (std::abs(det) < 1e-12) return Vec2{0.0};
    // Solve J^T F = tau.
    const double fx = (J[1][1] * tau1_ - J[1][0] * tau2_) / det;
    const double fy = (-J[0][1] * tau1_ + J[0][0] * tau2_) / det;
    return {fx, fy};
}

void PlanarArm::step_from(double h, Vec2 ext, const double J[2][2]) {
    // J-dot q-dot: the endpoint's centripetal acceleration, for the endpoint mass.
    const double c1 = c1_, s1 = s1_, c12 = c12_, s12 = s12_;
    const double w12 = w1_ + w2_;
    const Vec2 jdqd{-p_.l1 * c1 * w1_ * w1_ - p_.l2 * c12 * w12 * w12,
                    -p_.l1 * s1 * w1_ * w1_ - p_.l2 * s12 * w12 * w12};
    const double m = p_.endpoint_mass;
    // M = diag(I1, I2) + m J^T J
    const double M00 = p_.inertia1 + m * (J[0][0] * J[0][0] + J[1][0] * J[1][0]);
    const double M01 = m * (J[0][0] * J[0][1] + J[1][0] * J[1][1]);
    const double M11 = p_.inertia2 + m * (J[0][1] * J[0][1] + J[1][1] * J[1][1]);
    const Vec2 f = ext - m * jdqd;
    // Coulomb friction smoothed over 1 mrad/s. Beyond |x| = 22 glibc's tanh returns exactly +-1
    // (its own branch: 1 - tiny rounds to 1), so for a joint turning faster than 22 mrad/s the
    // exponentials are skipped with the same bits (tanh was about 9 % of a seed 000 trial; the
    // slower joints of its holds and slow slides still take it).
    auto friction = [&](double w) {
        const double x = w / 1e-3;
        return p_.friction * (std::abs(x) >= 22.0 ? std::copysign(1.0, x) : std::tanh(x));
    };
    const double r0 = tau1_ + J[0][0] * f.x + J[1][0] * f.y - p_.damping * w1_ - friction(w1_);
    const double r1 = tau2_ + J[0][1] * f.x + J[1][1] * f.y - p_.damping * w2_ - friction(w2_);
    const double det = M00 * M11 - M01 * M01;
    const double a1 = (M11 * r0 - M01 * r1) / det;
    const double a2 = (-M01 * r0 + M00 * r1) / det;
    // Semi-implicit Euler: velocities first, positions with the new velocities.
    w1_ += a1 * h;
    w2_ += a2 * h;
    const double q1 = q1_, q12 = q1_ + q2_;
    q1_ += w1_ * h;
    q2_ += w2_ * h;
    turn_trig(q1_ - q1, (q1_ + q2_) - q12);
}

double PlanarArm::cartesian_damping(Vec2 n) const {
    double J[2][2];
    jacobian_now(J);
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    // J^-1 n: the joint speeds that move the endpoint along n at 1 m/s.
    const double u1 = (J[1][1] * n.x - J[0][1] * n.y) / det;
    const double u2 = (-J[1][0] * n.x + J[0][0] * n.y) / det;
    return p_.damping * (u1 * u1 + u2 * u2);
}

double PlanarArm::min_cartesian_damping(Vec2 lo, Vec2 hi) const {
    PlanarArm probe(p_);
    double best = 1e300;
    for (int i = 0; i <= 8; ++i) {
        for (int j = 0; j <= 8; ++j) {
            const Vec2 x{lo.x + (hi.x - lo.x) * i / 8.0, lo.y + (hi.y - lo.y) * j / 8.0};
            if (!probe.place_at(x)) continue;
            double J[2][2];
            probe.jacobian_now(J);  // place_at took the sines at the placed angles
            // Cartesian damping D = B J^-T J^-1 = B (J J^T)^-1: smallest eigenvalue is
            // B / (largest eigenvalue of J J^T).
            const double a = J[0][0] * J[0][0] + J[0][1] * J[0][1];
            const double b = J[0][0] * J[1][0] + J[0][1] * J[1][1];
            const double c = J[1][0] * J[1][0] + J[1][1] * J[1][1];
            const double lmax = 0.5 * (a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b);
            best = std::min(best, p_.damping / lmax);
        }
    }
    return best;
}

}  // namespace contactlab::drivers::sim
