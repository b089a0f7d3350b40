// test_energy_balance.cpp — the per-tick energy terms (haptics/energy_balance.hpp) on analytic
// cases: the zero-order hold's K |dx|^2 / 2, a slide along a floor (hold and walk cancel), the pad
// turned into a floor (the hand's work, left out of what the loop generated), the ellipsoid's
// field term, friction's stick and slip; then the identity the split must keep on random ticks.
#include "haptics/energy_balance.hpp"
#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "scene_builders.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <random>

using namespace contactlab;

namespace {

constexpr double K = 1000.0;    // N/m
constexpr double kMax = 1.5;    // N
constexpr double kB = 1.0;      // N s/m, device damping
constexpr double kT = 1e-3;     // s

// The floor y = 0 from x = -0.1 to 0.1 m (solid below).
Scene floor_scene() { return test::scene_of({test::polyline({{-0.1, 0.0}, {0.1, 0.0}})}); }

EnergyLaw spring_law() { return {ForceLaw{}, K, kMax, kB}; }

// A frictionless tick with the proxy fixed at `p` (m), the finger at x (m), force held `f` (N).
EnergySample fixed_anchor(Vec2 x, Vec2 p, Vec2 f) {
    EnergySample s;
    s.finger = x;
    s.start = s.turned = s.proxy = s.anchor = p;
    s.applied = f;
    s.dt = kT;
    return s;
}

// A pad of R 20 mm and L 30 mm (half-angle 0.75 rad) whose centre rests 1 mm nearer the floor
// than R, turned to phi = 1.2 rad: only its end comes near the floor, clear of it. Lowered there
// from 2 mm above, so the proxy has its history.
struct TurningPad {
    Scene scene = [] {
        Scene s = floor_scene();
        s.finger.radius = 0.02;
        s.finger.length = 0.03;
        return s;
    }();
    Environment env = build_environment(scene);
    Proxy proxy{env, proxy_def_of(scene)};
    Vec2 x{0.0, 0.02 - 1e-3};  // m
    EnergyBalance balance;
    Vec2 applied{0.0};  // N, the force held since the last tick
    TurningPad() {
        for (int k = 0; k <= 20; ++k) proxy.update(x + Vec2{0.0, 2e-3 - 1e-4 * k}, 1.2);
    }
    // One tick with the finger held at x and turned to phi (rad): the balance's terms.
    EnergyTerms turn_to(double phi) {
        const ProxyOutput& o = proxy.update(x, phi);
        const EnergySample s{x, o.start, o.turned, o.proxy, o.anchor, applied, 1.0, kT, false, phi};
        applied = o.force;
        return balance.step(s, spring_law());
    }
};

}  // namespace

TEST_CASE("energy: the sampled spring's hold gains K |dx|^2 / 2 a tick, the damping takes b (n.dx)^2 / T") {
    // Wall at y = 0 seen by the finger centre (proxy) at y = 0, finger 1 mm in, moving 10 um deeper.
    EnergyBalance b;
    const Vec2 p{0.0, 0.0}, x0{0.0, -1e-3}, dx{0.0, -1e-5};
    const Vec2 f0 = K * (p - x0);  // 1 N up
    b.step(fixed_anchor(x0, p, Vec2{0.0}), spring_law());
    const EnergyTerms e = b.step(fixed_anchor(x0 + dx, p, f0), spring_law());
    // F_{k-1} . dx + K ((d + dd)^2 - d^2) / 2 = K dd^2 / 2 exactly for a linear spring.
    CHECK(e.hold == doctest::Approx(0.5 * K * 1e-10).epsilon(1e-9));
    CHECK(e.damping == doctest::Approx(-kB * 1e-10 / kT).epsilon(1e-9));
    CHECK(e.turn == 0.0);
    CHECK(e.proxy == 0.0);
    CHECK(e.friction == 0.0);
    CHECK(e.field == 0.0);
    // K T / 2 < b: the tick dissipated more than the hold made (Colgate & Schenkel's bound).
    CHECK(e.generated() < 0.0);
}

TEST_CASE("energy: sliding along a flat floor, the walk gives back what the hold counted") {
    // Floor y = 0, pad radius R: the proxy's centre rests at y = R; the finger 1 mm below it.
    const Scene scene = floor_scene();
    const Environment env = build_environment(scene);
    Proxy proxy(env, proxy_def_of(scene));
    const double R = scene.finger.radius;
    EnergyBalance b;
    Vec2 applied{0.0};
    double hold = 0.0, walk = 0.0;
    for (int k = 0; k <= 200; ++k) {
        const Vec2 x{-0.01 + 1e-4 * k, R - 1e-3};  // 10 cm/s at 1 kHz along the floor
        const ProxyOutput& o = proxy.update(x, 0.0);
        const EnergySample s{x, o.start, o.turned, o.proxy, o.anchor, applied, 1.0, kT};
        const EnergyTerms e = b.step(s, spring_law());
        if (k > 1) {
            // F is normal, the motion tangential: F . dx = 0 and U unchanged, tick by tick.
            CHECK(e.hold + e.proxy == doctest::Approx(0.0).scale(1e-12));
            CHECK(e.turn == 0.0);
            hold += e.hold;
            walk += e.proxy;
        }
        applied = o.force;
    }
    // Each tick the held anchor falls 0.1 mm behind: K (0.1 mm)^2 / 2 = 5 uJ, given back by the walk.
    CHECK(hold == doctest::Approx(199 * 0.5 * K * 1e-8).epsilon(1e-6));
    CHECK(walk == doctest::Approx(-hold).epsilon(1e-9));
}

TEST_CASE("energy: the pad turned into the floor is the hand's work, not the loop's") {
    // The finger's centre held still 1 mm nearer the floor than R, the pad (half-angle L / 2R =
    // 0.75 rad) turned 1.2 rad away so that only its end comes near the floor, clear of it. Turning
    // phi back to 0.4 rad sweeps the pad's end into the floor: the re-projection pushes the proxy
    // up to R above it. The spring's energy rises from 0 to K (1 mm)^2 / 2 with no motion: all of
    // it is `turn`, and what the loop generated stays zero.
    TurningPad pad;
    double turn = 0.0, u_first = 0.0, u_last = 0.0;
    for (int k = 0; k <= 100; ++k) {
        const EnergyTerms e = pad.turn_to(1.2 - 0.008 * k);  // rad
        const double u = law_energy(ForceLaw{}, K, kMax, pad.x, pad.proxy.output().anchor, Vec2{0.0, 1.0});
        if (k == 0) u_first = u;
        u_last = u;
        CHECK(e.hold == 0.0);  // no motion, no hold
        CHECK(e.generated() <= 1e-15);
        turn += e.turn;
    }
    CAPTURE(u_first);
    CAPTURE(u_last);
    CHECK(u_first == 0.0);  // the pad's end clear of the floor
    CHECK(u_last == doctest::Approx(0.5 * K * 1e-6).epsilon(1e-6));  // the pad's bottom 1 mm in
    CHECK(turn == doctest::Approx(u_last - u_first).epsilon(1e-9));
}

TEST_CASE("energy: a pad turned into the floor and back out, again and again, nets zero for the loop") {
    // Turning out pushes nothing: the walk brings the proxy back and releases the energy the turn
    // in stored. That release is the hand's too (a finger-angle encoder toggling one count at a
    // pad-end contact must not credit the loop with dissipation it never did).
    TurningPad pad;
    double generated = 0.0, turn = 0.0, released = 0.0;
    for (int cycle = 0; cycle < 5; ++cycle) {
        for (int k = 0; k <= 200; ++k) {
            const EnergyTerms e = pad.turn_to(1.2 - 0.8 * (k <= 100 ? k : 200 - k) / 100.0);  // rad: in to 0.4, back out to 1.2
            generated += e.generated();
            turn += e.turn;
            if (e.turn < 0.0) released -= e.turn;
        }
    }
    CAPTURE(turn);
    CAPTURE(released);
    // Each cycle stores and releases K (1 mm)^2 / 2 = 0.5 mJ through the turn.
    CHECK(released == doctest::Approx(5 * 0.5 * K * 1e-6).epsilon(1e-6));
    CHECK(std::abs(turn) < 1e-12);
    CHECK(std::abs(generated) < 1e-12);
}

TEST_CASE("energy: the ellipsoid's field term is its anisotropy, r^2 dg / 2, as the penetration turns") {
    ForceLaw law;
    law.model = ForceModel::ellipsoid;
    law.k_tangential = 2000.0;
    law.k_normal = 500.0;
    const EnergyLaw L{law, 500.0, 10.0, kB};  // clamp out of reach: the linear field
    EnergyBalance b;
    const Vec2 a{0.0, 0.0}, n{0.0, 1.0};
    const double r = 1e-3;  // m
    // Around the anchor at constant radius from straight below (k_normal) to the side (k_tangential).
    double field = 0.0, hold = 0.0;
    Vec2 applied{0.0};
    const int steps = 1000;
    for (int k = 0; k <= steps; ++k) {
        const double th = -0.5 * kPi + 0.5 * kPi * k / steps;  // rad, from -n to +t
        const Vec2 x = a + r * Vec2{std::cos(th), std::sin(th)};
        EnergySample s = fixed_anchor(x, a, applied);
        s.proxy = s.turned = s.start = x + r * n;  // a frictionless proxy straight above (no offset energy change)
        s.anchor = a;
        const EnergyTerms e = b.step(s, L);
        if (k > 0) {
            field += e.field;
            hold += e.hold;
        }
        applied = ellipsoid_force(x - a, n, law.k_tangential, law.k_normal);
    }
    // U = g r^2 / 2 along each ray: from g = k_normal to g = k_tangential.
    CHECK(field == doctest::Approx(0.5 * r * r * (2000.0 - 500.0)).epsilon(1e-3).scale(0.0));
    // The central force does no work on a circle about its anchor: the hold is the sampling alone,
    // O(dtheta) of the field's share.
    CHECK(std::abs(hold) < 0.01 * field);
}

TEST_CASE("energy: friction loads while the finger sticks and releases when it slips") {
    // The stiction anchor held at the origin while the frictionless proxy follows the finger
    // sideways: the offset's energy grows (friction > 0) as the walk's falls; a slip that moves the
    // anchor toward the proxy releases it (friction < 0).
    EnergyBalance b;
    const EnergyLaw L = spring_law();
    auto sample = [](Vec2 x, Vec2 proxy, Vec2 anchor, Vec2 f) {
        EnergySample s;
        s.finger = x;
        s.start = s.turned = s.proxy = proxy;
        s.anchor = anchor;
        s.applied = f;
        s.dt = kT;
        return s;
    };
    const double d = 1e-3;  // m
    b.step(sample({0.0, -d}, {0.0, 0.0}, {0.0, 0.0}, Vec2{0.0}), L);
    const EnergyTerms stick = b.step(sample({1e-4, -d}, {1e-4, 0.0}, {0.0, 0.0}, K * Vec2{0.0, d}), L);
    CHECK(stick.friction > 0.0);
    CHECK(stick.friction == doctest::Approx(0.5 * K * 1e-8).epsilon(1e-9));  // the offset 0.1 mm
    const EnergyTerms slip = b.step(sample({1e-4, -d}, {1e-4, 0.0}, {0.5e-4, 0.0}, K * Vec2{-1e-4, d}), L);
    CHECK(slip.friction < 0.0);
}

TEST_CASE("energy: the terms add up to F . dx + U_k - U_{k-1} on random ticks (spring and ellipsoid)") {
    std::mt19937_64 rng(25);
    std::uniform_real_distribution<double> u(-2e-3, 2e-3);
    for (int model = 0; model < 2; ++model) {
        ForceLaw law;
        if (model == 1) {
            law.model = ForceModel::ellipsoid;
            law.k_tangential = 1500.0;
            law.k_normal = 600.0;
            law.field_angle = 0.3;
        }
        const EnergyLaw L{law, 800.0, 1.2, kB};
        EnergyBalance b;
        EnergySample prev{};
        double u_prev = 0.0;
        for (int k = 0; k < 2000; ++k) {
            EnergySample s;
            s.finger = {u(rng), u(rng)};
            s.start = s.finger + Vec2{u(rng), u(rng)};
            s.turned = s.finger + Vec2{u(rng), u(rng)};
            s.proxy = s.finger + Vec2{u(rng), std::abs(u(rng)) + 1e-6};
            s.anchor = k % 3 == 0 ? s.proxy : s.proxy + Vec2{u(rng), 0.0};
            s.applied = {u(rng) * 500.0, u(rng) * 500.0};
            s.share = 0.5 + 0.5 * (k % 2);
            s.swapped = k % 7 == 0;
            s.phi = k % 5 == 0 ? 0.01 * k : prev.phi;  // rad: some ticks turn the finger
            s.dt = kT;
            const Vec2 n = glm::normalize(s.proxy - s.finger);
            const double u_now = s.share * law_energy(law, L.stiffness, L.max_force, s.finger, s.anchor, n);
            // This tick's share weighs both ends (the balance's rule for the ramp).
            const Vec2 n_prev = k > 0 ? glm::normalize(prev.proxy - prev.finger) : n;
            u_prev = k > 0 ? s.share * law_energy(law, L.stiffness, L.max_force, prev.finger, prev.anchor, n_prev) : 0.0;
            const EnergyTerms e = b.step(s, L);
            if (k > 0) {
                const double sum = e.hold + e.field + e.turn + e.edit + e.proxy + e.friction;
                const double expected = glm::dot(s.applied, s.finger - prev.finger) + u_now - u_prev;
                CHECK(sum == doctest::Approx(expected).scale(1e-9));
                if (!s.swapped) CHECK(e.edit == 0.0);
            }
            prev = s;
        }
    }
}
