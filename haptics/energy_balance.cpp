// energy_balance.cpp — the per-tick energy terms (see energy_balance.hpp).
#include "haptics/energy_balance.hpp"

#include <algorithm>
#include <cmath>

namespace contactlab {

double spring_energy(double depth, double k, double max_force) noexcept {
    if (!(depth > 0.0) || !(k > 0.0)) return 0.0;
    const double d_clamp = max_force / k;  // m: depth where the clamp starts
    if (depth <= d_clamp) return 0.5 * k * depth * depth;
    return 0.5 * k * d_clamp * d_clamp + max_force * (depth - d_clamp);
}

namespace {
// N/m: the law's force per metre along the unit direction u of the penetration x - a.
double ray_stiffness(const ForceLaw& law, double stiffness, Vec2 u, Vec2 n) noexcept {
    if (law.model != ForceModel::ellipsoid) return stiffness;
    return glm::length(ellipsoid_force(u, n, law.k_tangential, law.k_normal, law.field_angle));
}
}  // namespace

double law_energy(const ForceLaw& law, double stiffness, double max_force, Vec2 x, Vec2 a, Vec2 n) noexcept {
    const Vec2 p = x - a;  // m
    const double r = glm::length(p);
    if (!(r > 0.0)) return 0.0;
    return spring_energy(r, ray_stiffness(law, stiffness, p / r, n), max_force);
}

EnergyTerms EnergyBalance::step(const EnergySample& s, const EnergyLaw& L) noexcept {
    EnergyTerms e;
    const Vec2 d = s.proxy - s.finger;
    const double depth = glm::length(d);
    // The contact frame the force law used this tick (Proxy::apply_force_law): finger toward proxy.
    const Vec2 n = depth > 0.0 ? d / depth : prev_normal_;
    const auto U = [&](Vec2 x, Vec2 a, Vec2 nn) {
        return s.share * law_energy(L.law, L.stiffness, L.max_force, x, a, nn);
    };
    if (primed_) {
        const Vec2 dx = s.finger - prev_x_;  // m
        motion_ = dx;
        // The sampled spring with its anchor held where the last tick left it.
        const double u_before = U(prev_x_, prev_anchor_, prev_normal_);
        const double u_moved = U(s.finger, prev_anchor_, prev_normal_);
        e.hold = glm::dot(s.applied, dx) + u_moved - u_before;
        if (L.law.model == ForceModel::ellipsoid) {
            // The field's own share of that: at the mean radius, the change of the ray stiffness
            // between the two directions of the penetration (the continuous field's r^2 dg / 2).
            const Vec2 p0 = prev_x_ - prev_anchor_, p1 = s.finger - prev_anchor_;
            const double r0 = glm::length(p0), r1 = glm::length(p1);
            if (r0 > 0.0 && r1 > 0.0) {
                const double r = 0.5 * (r0 + r1);
                const double g0 = ray_stiffness(L.law, L.stiffness, p0 / r0, prev_normal_);
                const double g1 = ray_stiffness(L.law, L.stiffness, p1 / r1, prev_normal_);
                e.field = s.share * (spring_energy(r, g1, L.max_force) - spring_energy(r, g0, L.max_force));
                e.hold -= e.field;
            }
            // ... and the field's axes turning with the contact frame.
            e.field += U(s.finger, prev_anchor_, n) - u_moved;
        }
        // The anchor's way from last tick's to this tick's, at the new finger position. Most ticks
        // most of these points coincide (no turn, no swap, no friction): each is evaluated once.
        // (The spring's U ignores the normal, so its u_moved is the anchor's too.)
        const double u_anchor_before =
            L.law.model == ForceModel::ellipsoid ? U(s.finger, prev_anchor_, n) : u_moved;
        const double u_proxy_before = prev_proxy_ == prev_anchor_ ? u_anchor_before : U(s.finger, prev_proxy_, n);
        const double u_start = s.start == prev_proxy_ ? u_proxy_before : U(s.finger, s.start, n);
        const double u_turned = s.turned == s.start ? u_start : U(s.finger, s.turned, n);
        const double u_proxy = s.proxy == s.turned ? u_turned : U(s.finger, s.proxy, n);
        const double u_anchor = s.anchor == s.proxy ? u_proxy : U(s.finger, s.anchor, n);
        e.edit = s.swapped ? u_start - u_proxy_before : 0.0;
        e.turn = u_turned - u_start;
        e.proxy = u_proxy - u_turned + (s.swapped ? 0.0 : u_start - u_proxy_before);
        e.friction = (u_anchor - u_proxy) - (u_anchor_before - u_proxy_before);
        if (s.swapped) {  // the new scene's proxy holds no stiction point yet: the swap's doing
            e.edit += e.friction;
            e.friction = 0.0;
        }
        if (s.phi != prev_phi_) {
            // The walk's release beyond the hold's share on a turning tick: the pad turned back
            // out, the hand's (see the header).
            const double beyond = e.proxy + std::max(0.0, e.hold);  // J
            if (beyond < 0.0) {
                e.proxy -= beyond;
                e.turn += beyond;
            }
        }
        // The device's damping b dissipated b v^2 over the period, of which only the motion along
        // the spring's line of action pays for what the spring generated: motion across it
        // (sliding, driven by the hand) would credit the loop with dissipation the hand pays for
        // and hide a bounce along the normal (seen at 100 Hz while sliding at 0.19 m/s: -8 mJ of
        // credit against a 1.5 N bounce). Before any force, the whole motion.
        if (glm::dot(s.applied, s.applied) > 0.0) line_ = s.applied / glm::length(s.applied);
        const double along = glm::dot(line_, dx);  // m
        const double dx2 = glm::dot(line_, line_) > 0.0 ? along * along : glm::dot(dx, dx);  // m^2
        e.damping = -L.device_damping * dx2 / s.dt;
    }
    prev_x_ = s.finger;
    prev_proxy_ = s.proxy;
    prev_anchor_ = s.anchor;
    prev_normal_ = n;
    prev_phi_ = s.phi;
    primed_ = true;
    return e;
}

}  // namespace contactlab
